// SPDX-License-Identifier: MIT
// A boulder's impact on a rigid barrier by Hertz's elastic contact with a load reduction factor K_c
// (docs/design.md): a sphere of radius r_B, mass m_B and speed v_B on a half-space,
//   k_X = (1 − ν_X²)/(π E_X),  n = 4 sqrt(r_B) / (3π (k_B + k_b)),  α = (5 m_B v_B² / (4 n))^0.4,
//   F = K_c n α^1.5 = K_c C r_B² v_B^1.2.
// SI units: E in Pa, r in m, ρ in kg/m³, v in m/s, F in N.
#pragma once
#include <string>
#include <vector>

namespace sabo::analysis::design {

struct Elastic {
    double youngs_modulus = 0.0;              // E, Pa
    double poisson = 0.0;                     // ν
    [[nodiscard]] double compliance() const;  // k = (1 − ν²)/(π E), 1/Pa
};
// Defaults: the materials the closed forms of the literature assume.
inline constexpr Elastic concrete{30e9, 0.2};
inline constexpr Elastic granite{60e9, 0.25};

struct Boulder {
    double radius = 0.0;    // r_B, m
    double density = 0.0;   // kg/m³
    double velocity = 0.0;  // v_B, m/s
    [[nodiscard]] double mass() const;
};

struct HertzImpact {
    double stiffness = 0.0;      // n, N/m^1.5
    double indentation = 0.0;    // α, m: the largest approach of the elastic sphere and half-space
    double elastic_force = 0.0;  // n α^1.5, N (K_c = 1)
};
[[nodiscard]] HertzImpact hertz_impact(const Boulder& b, const Elastic& boulder, const Elastic& barrier);
// C of F = K_c C r² v^1.2 for these materials and boulder density, N/(m² (m/s)^1.2).
[[nodiscard]] double hertz_closed_form_constant(double boulder_density, const Elastic& boulder,
                                                const Elastic& barrier);

// The load reduction factors of the literature (F = K_c n α^1.5).
struct ReductionFactor {
    std::string reference;
    double k_c = 0.0;
};
[[nodiscard]] const std::vector<ReductionFactor>& load_reduction_factors();

// The closed forms F = K̂ v^1.2 r² as the review lists them; K̂ in kN or in tonnes-force (tf) per
// (m² (m/s)^1.2), the unit read from the K_c each implies for concrete and granite (docs/design.md).
struct ClosedForm {
    double k_hat = 0.0;
    double newtons_per_unit = 0.0;                                     // 1000 (kN) or 9806.65 (tf)
    std::string unit;                                                  // "kN" | "tf"
    [[nodiscard]] double force(double velocity, double radius) const;  // N
};
[[nodiscard]] const std::vector<ClosedForm>& hertz_closed_forms();

}  // namespace sabo::analysis::design
