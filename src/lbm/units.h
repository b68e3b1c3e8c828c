// SPDX-License-Identifier: MIT
// SI ↔ lattice units (docs/lbm.md): one converter for every quantity. Lattice units take Δx, Δt and
// the fluid's reference density ρ_f as 1; a quantity with SI dimension m^a s^b kg^c scales by
// Δx^a Δt^b ρ_f^c Δx^(3c).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace sabo::lbm {

class UnitConverter {
  public:
    // Throws InputError unless all three are positive and finite.
    UnitConverter(double dx_m, double dt_s, double density_kg_m3);

    [[nodiscard]] double dx() const { return dx_; }
    [[nodiscard]] double dt() const { return dt_; }
    [[nodiscard]] double density() const { return rho_; }

    // SI → lattice
    [[nodiscard]] double velocity(double u_m_s) const { return u_m_s * dt_ / dx_; }
    [[nodiscard]] double kinematic_viscosity(double nu_m2_s) const { return nu_m2_s * dt_ / (dx_ * dx_); }
    [[nodiscard]] double acceleration(double a_m_s2) const { return a_m_s2 * dt_ * dt_ / dx_; }
    // stress or pressure divided by ρ_f (what a lattice stress is, with ρ ≈ 1)
    [[nodiscard]] double stress(double p_Pa) const { return p_Pa / rho_ * dt_ * dt_ / (dx_ * dx_); }
    [[nodiscard]] double strain_rate(double rate_1_s) const { return rate_1_s * dt_; }
    // BGK relaxation time for a kinematic viscosity: τ = ½ + 3 ν Δt/Δx²
    [[nodiscard]] double tau(double nu_m2_s) const { return 0.5 + 3.0 * kinematic_viscosity(nu_m2_s); }

    // lattice → SI
    [[nodiscard]] double velocity_si(double u) const { return u * dx_ / dt_; }
    [[nodiscard]] double acceleration_si(double a) const { return a * dx_ / (dt_ * dt_); }
    [[nodiscard]] double force_si(double f) const { return f * rho_ * dx_ * dx_ * dx_ * dx_ / (dt_ * dt_); }
    [[nodiscard]] double mass_si(double m) const { return m * rho_ * dx_ * dx_ * dx_; }
    [[nodiscard]] double stress_si(double p) const { return p * rho_ * dx_ * dx_ / (dt_ * dt_); }
    [[nodiscard]] double strain_rate_si(double rate) const { return rate / dt_; }

  private:
    double dx_, dt_, rho_;
};

// What a fluid set-up asks of the lattice; check_lattice() derives the lattice numbers and refuses
// unstable or oversize set-ups (docs/lbm.md).
struct LatticeRequest {
    double dx_m = 0.0, dt_s = 0.0;
    double density_kg_m3 = 0.0;
    double viscosity_Pa_s = 0.0;      // η (Newtonian) or the plastic viscosity η0 (Bingham)
    double yield_stress_Pa = 0.0;     // τ0; 0: Newtonian
    double velocity_scale_m_s = 0.0;  // the fastest flow expected (Mach check)...
    std::string velocity_key;         // ...and the key that sets it (empty: derived), for messages
    double gravity_m_s2 = 0.0;        // |g| (0: no gravity), for the hydrostatic check over...
    double depth_m = 0.0;             // ...the deepest the fluid stands at rest, m
    double tau_min = 0.501, tau_max = 1.8;
    std::size_t nodes = 0;
    std::size_t stored_nodes = 0;  // nodes and the padding of the lattice's rows (0: as many as nodes)
    std::size_t bytes_per_node = 0;
    std::size_t memory_limit_bytes = 0;                // 0: no limit
    double grain_d_mean_m = 0.0, grain_d_min_m = 0.0;  // 0: no grains
    std::string where;                                 // the case file, for messages
};

struct LatticeNumbers {
    double nu_lb = 0.0;     // ν_LB of η (or η0)
    double tau = 0.0;       // its τ (Bingham: the plastic τ, the lower bound of the cells' τ)
    double u_lb = 0.0;      // velocity scale in lattice units
    double mach = 0.0;      // u_LB sqrt(3)
    double yield_lb = 0.0;  // τ0/ρ_f in lattice units
    // The density the deepest column of fluid varies by under gravity, relative: the lattice's pressure is
    // c_s² ρ, so Δρ/ρ = 3 g H Δt²/Δx² (the weakly compressible fluid's hydrostatic error).
    double hydrostatic_variation = 0.0;
    std::size_t memory_bytes = 0;
    std::vector<std::string> warnings;
};

// Throws InputError naming the request's `where`, the quantity and its allowed range when τ is
// outside (0.5, τ_max], Mach ≥ 1, the hydrostatic density variation over the fluid's depth exceeds
// max_hydrostatic_variation, Δx > d_mean/4, or the nodes do not fit the memory limit; returns warnings for
// Mach ≥ 0.3, a hydrostatic variation above warn_hydrostatic_variation, Δx > d_min/10 and τ below τ_min
// (clamped in the cells).
inline constexpr double warn_hydrostatic_variation = 0.01, max_hydrostatic_variation = 0.10;
[[nodiscard]] LatticeNumbers check_lattice(const LatticeRequest& req);

// One line per derived number, for the start-up printout.
[[nodiscard]] std::vector<std::string> describe(const LatticeRequest& req, const LatticeNumbers& n);

}  // namespace sabo::lbm
