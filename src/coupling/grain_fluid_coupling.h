// SPDX-License-Identifier: MIT
// The grain–fluid coupling (Leonardi et al. 2016, simplified immersed boundary; or partially saturated
// cells, Noble & Torczynski 1998): every lattice step, the cells a grain covers (grain_cells.h: those whose
// centre it holds, or every cell it cuts with its solid fraction ε) exchange F_h with it (lbm::SolidExchange:
// the drag B λ ρ (u_f − v_p), or the partially saturated collision; B the lattice's saturation_weight(ε, τ),
// 1 in a wholly covered cell; the fluid gets −F_h, the grain +F_h and the torque (x − x_p) × F_h), then the
// grains take n_sub DEM steps of Δt_LBM / n_sub with that force and torque held. With `buoyancy` each grain
// also gets Archimedes' force for the share of its volume whose fluid the lattice weighs (no reaction on the
// fluid, which carries its own weight there): the whole volume by the cell-centre rule (without the term the
// scheme has none), the share ε − B of each cell with partially saturated cells (whose exchange carries the
// pressure on the share B). Its volume: the sphere's, V_p Σ λ (ε − B) / N (N = Σ ε of the cells the sphere
// would cover alone on the grid; a grain under the surface gets exactly −ρ_f g V_p by the cell-centre rule
// wherever it lies), or the cells' Σ λ (ε − B) Δx³ (by the cell-centre rule it swings by several per cent of
// V_p as the grain moves across the cells at d/Δx ~ 8). docs/coupling.md.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/vec3.h"
#include "coupling/grain_cells.h"
#include "coupling/opencl/device_grain_cells.h"
#include "dem/dem_solver.h"
#include "lbm/fluid_lattice.h"
#include "lbm/units.h"

namespace sabo::coupling {

enum class BuoyancyVolume : std::uint8_t { sphere, cells };
inline constexpr std::array<std::string_view, 2> buoyancy_volume_names{"sphere", "cells"};
[[nodiscard]] inline std::string_view name(BuoyancyVolume v) {
    return buoyancy_volume_names[static_cast<std::size_t>(v)];
}

struct CouplingSettings {
    CoverRule model = CoverRule::cell_centre;  // which cells a grain covers, and how much of each
    bool buoyancy = true;
    BuoyancyVolume volume = BuoyancyVolume::sphere;
    int substeps = 1;  // n_sub: DEM steps per lattice step
    Vec3 gravity{};    // m/s², for the buoyancy
};

// A grain that covers cells of this lattice but is integrated elsewhere: in a run divided among MPI ranks, a
// neighbour's grain reaching past the common face (parallel/grain_visitors.h). State at the lattice step's
// start.
struct VisitingGrain {
    Vec3 x{}, v{}, w{};  // m, m/s, rad/s
    double r = 0.0;      // m
};

// What the last exchange gave the grains, summed over all of them (SI; in a divided run, over the cells of
// this rank's planes).
struct ExchangeTotals {
    Vec3 drag{};            // Σ F_h, N
    Vec3 buoyancy{};        // Σ F_b, N
    std::size_t cells = 0;  // grain cells
};

class GrainFluidCoupling {
  public:
    // `units` is the lattice's converter (Δx, Δt_LBM, ρ_f); `origin` the lattice's lower corner in the
    // grains' frame, m.
    GrainFluidCoupling(const CouplingSettings& settings, const lbm::UnitConverter& units, const Vec3& origin);

    // The parts of a coupled step (sim::Simulation::step() calls them around the lattice step, then takes
    // the n_sub DEM steps): the grain cells from the grains' state before the lattice step, the drag and
    // buoyancy set as the grains' external force after it.
    template <class Real>
    void before_fluid_step(const dem::Particles& p, lbm::FluidLattice<Real>& lattice) {
        before_fluid_step(p, p.n_mobile, {}, lattice);
    }
    template <class Real>
    void after_fluid_step(const lbm::FluidLattice<Real>& lattice, dem::DemSolver& grains);

    // The parts for a lattice that is a slab of a divided run: the cells covered by the first `own` grains
    // of `p` and by `visitors` (ghost planes included: they are stepped too); after the lattice step, the
    // drag (+ buoyancy) and its torque on each of them from the own planes' cells (own grains first, then
    // the visitors), to be set on the own grains and sent back to the visitors' owners.
    template <class Real>
    void before_fluid_step(const dem::Particles& p, std::size_t own, std::span<const VisitingGrain> visitors,
                           lbm::FluidLattice<Real>& lattice);
    template <class Real>
    void find_forces(const lbm::FluidLattice<Real>& lattice);
    // The same exchange with a lattice stepping on a device (coupling/opencl): the grains' cells found and
    // covered there from the grains' state (only centres, radii and velocities go up), then each grain's
    // sums read back (a slab's: of its own planes' cells), the buoyancy added as above. `lattice`: the
    // host's lattice of the device's (its shape, strides and slab).
    template <class Real>
    void before_device_step(const dem::Particles& p, std::size_t own, std::span<const VisitingGrain> visitors,
                            const lbm::FluidLattice<Real>& lattice, opencl::DeviceGrainCells& cells);
    void find_forces(opencl::DeviceGrainCells& cells);
    [[nodiscard]] std::span<const Vec3> forces() const { return force_; }
    [[nodiscard]] std::span<const Vec3> torques() const { return torque_; }
    // The buoyancy part of forces(), per covering grain, N (zero without buoyancy); the drag is the rest.
    [[nodiscard]] std::span<const Vec3> buoyancies() const { return buoyancy_; }

    [[nodiscard]] const ExchangeTotals& last_exchange() const { return totals_; }
    [[nodiscard]] const CouplingSettings& settings() const { return settings_; }
    [[nodiscard]] const lbm::UnitConverter& units() const { return units_; }
    // What outlives a step (io/checkpoint.h): the last exchange's totals. The grain cells, their weights
    // and the forces are found anew from the grains at every step.
    template <class Archive>
    void transfer(Archive& a) {
        a(totals_);
    }

  private:
    CouplingSettings settings_;
    lbm::UnitConverter units_;
    Vec3 origin_;
    GrainCellFinder finder_;
    std::vector<Vec3> x_, v_, w_;  // the covering grains: own mobile grains, then visitors
    std::vector<double> r_;
    std::vector<double> volume_per_cell_;  // per covering grain: V_p / N, m³ (the sphere's volume)
    // x_, v_, w_, r_: the first `own` grains of `p`, then the visitors
    void take_grains(const dem::Particles& p, std::size_t own, std::span<const VisitingGrain> visitors);
    // the lattice's cells in the grains' frame
    template <class Real>
    [[nodiscard]] LatticeFrame frame_of(const lbm::FluidLattice<Real>& lattice) const;
    // volume_per_cell_ of the covering grains in x_, r_ (with the sphere's buoyancy volume)
    void share_volumes(const LatticeFrame& frame);
    std::vector<lbm::SolidCell> lattice_cells_;
    std::vector<double> weight_;        // λ ε of each grain cell when it was found
    std::vector<Vec3> force_, torque_;  // per covering grain: the drag (+ buoyancy) and its torque, SI
    std::vector<Vec3> buoyancy_;        // per covering grain: the buoyancy in force_, N
    ExchangeTotals totals_;
};

}  // namespace sabo::coupling
