// SPDX-License-Identifier: MIT
// The macroscopic state of a lattice's own planes, as observers and writers read it (never the populations
// or the per-cell storage: what a lattice on another backend hands back after a step). Cells in image order:
// x fastest over the own planes, then y, then z, no padding. Filled by FluidLattice::snapshot(), which reuses
// the arrays (no allocation once they have the lattice's size); totals, interface count and clamps are the
// lattice's own numbers of the same state, summed in the same order.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace sabo::lbm {

enum class CellType : std::uint8_t { fluid = 0, interface = 1, gas = 2, obstacle = 3 };

// Outlets a lattice may have (FluidLattice::set_outlet): sets of cells through which fluid leaves the domain.
inline constexpr std::size_t max_outlets = 4;

// A cell's place in a lattice's region (FluidLattice::set_region) and in the sums a run's observers read
// (the bits Simulation::set_fluid_region's function gives each cell's centre).
enum RegionBits : std::uint8_t {
    region_downstream = 1,   // in the region (a debris run's: behind its barrier); FluidSummary::region_mass
    region_above_crest = 2,  // what enters the region from such a cell counts as over the barrier's crest
};

struct FluidTotals {
    double mass = 0.0;       // lattice units
    double max_speed = 0.0;  // lattice units
};

struct ClampCounts {
    std::uint64_t at_min = 0, at_max = 0;  // cells on the τ_min / τ_max clamp in the last step
};

struct FluidFields {
    int nx = 0, ny = 0, nz = 0;  // own planes, cells across, cells up
    int first_x = 0;             // the lattice's local x of the first own plane (its own_begin)
    std::vector<CellType> type;
    std::vector<std::uint8_t> covered;  // 1: a moving solid covers the cell (FluidLattice::set_solid_cells)
    std::vector<double> fill;           // λ: 1 fluid, 0 gas and obstacle, m/ρ interface
    std::vector<double> density;        // ρ, lattice units (fluid and interface cells; 0 elsewhere)
    std::vector<Vec3> velocity;         // u of the collision, (Σ f c + F/2)/ρ, lattice units (idem)
    std::vector<double> tau;            // relaxation time of the cell's last collision
    FluidTotals totals;                 // FluidLattice::totals() of the own planes
    std::size_t interface_cells = 0;    // in the own planes
    ClampCounts clamps;                 // of the last step (a slab's: ghost planes included)
    // mass that left through each outlet since the start, lattice units (a slab's: its own planes'); the
    // lattice's mass plus these is its starting mass, to round-off
    std::array<double, max_outlets> drained{};
    // mass that entered the lattice's region since the start (FluidLattice::region_inflow)
    std::array<double, 3> region_inflow{};

    // Sizes the arrays for `planes` planes of ny × nz cells, the first at the lattice's local x `first`
    // (no allocation once they have that size); the values are the filler's to write.
    void shape(int planes, int cells_across, int cells_up, int first) {
        nx = planes;
        ny = cells_across;
        nz = cells_up;
        first_x = first;
        const std::size_t n =
            static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
        type.resize(n);
        covered.resize(n);
        fill.resize(n);
        density.resize(n);
        velocity.resize(n);
        tau.resize(n);
    }
    // The cell at (x, y, z), x counted from the first own plane.
    [[nodiscard]] std::size_t cell(int x, int y, int z) const {
        return static_cast<std::size_t>(x) +
               static_cast<std::size_t>(nx) *
                   (static_cast<std::size_t>(y) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(z));
    }
    [[nodiscard]] std::size_t cells() const { return type.size(); }
    [[nodiscard]] bool wet(std::size_t c) const {
        return type[c] == CellType::fluid || type[c] == CellType::interface;
    }
    // What one snapshot holds per cell, for the memory estimate of a run.
    static constexpr std::size_t bytes_per_cell = sizeof(CellType) + 1 + 3 * sizeof(double) + sizeof(Vec3);
};

}  // namespace sabo::lbm
