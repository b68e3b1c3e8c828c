// SPDX-License-Identifier: MIT
// What the observers of a series row read of the fluid: a few sums over the own planes instead of every
// cell's fields. A lattice on a device makes them there (lbm/opencl/), so that a row does not copy the
// whole lattice back; on the CPU they are summed from the snapshot (lbm/fluid_fields.h).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "lbm/fluid_fields.h"

namespace sabo::lbm {

struct FluidSummary {
    int first_x = 0;     // the lattice's local x of the first own plane (FluidFields::first_x)
    int nz = 0;          // cells up
    FluidTotals totals;  // the wet cells' mass (ρ, or an interface cell's m) and largest speed
    std::size_t interface_cells = 0;
    ClampCounts clamps;                         // of the last step
    std::array<double, max_outlets> drained{};  // FluidFields::drained
    double free_mass = 0.0;                     // λρ of the wet cells no moving solid covers, lattice units
    double region_mass = 0.0;                   // of those, the cells downstream (region_downstream)
    std::array<double, 3> region_inflow{};      // FluidFields::region_inflow
    int front_x = -1;  // the highest x (from the first own plane) of a wet cell with λ ≥ 0.1; −1: none
    int top_z = -1;    // the highest z of such a cell
};

// The summary of `fields`, summed in their order; `region(x, y, z)` (x from the first own plane) gives a
// cell's RegionBits (none: 0 for every cell).
[[nodiscard]] FluidSummary summarize(const FluidFields& fields,
                                     const std::function<std::uint8_t(int, int, int)>& region);

}  // namespace sabo::lbm
