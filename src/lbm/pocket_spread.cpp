// SPDX-License-Identifier: MIT
// Where a closed gas pocket's volume comes from (docs/lbm.md, "What the spread moves"): an enclosed
// interface cell fills whatever its mass, and its deficit is taken from the interface cells near it,
// reachable through the fluid, instead of from the whole surface.
#include <fmt/format.h>

#include "core/error.h"
#include "lbm/fluid_lattice.h"

namespace sabo::lbm {

template <class Real>
void FluidLattice<Real>::set_pocket_reach(int cells) {
    if (cells < 0 || cells > 8)
        throw InputError(fmt::format("the pocket's reach {} cells is outside [0, 8]", cells));
    pocket_reach_ = cells;
    if (cells > 0) {  // once, before the steps: the search's marks and lists
        scratch_.pocket_stamp.assign(n_, 0);
        const auto cube = static_cast<std::size_t>((2 * cells + 1) * (2 * cells + 1) * (2 * cells + 1));
        scratch_.pocket_queue.reserve(cube);
        scratch_.pocket_receivers.reserve(cube);
    }
}

template <class Real>
bool FluidLattice<Real>::spread_pocket(std::uint32_t k, double deficit) {
    auto& stamp = scratch_.pocket_stamp;
    auto& queue = scratch_.pocket_queue;
    auto& receivers = scratch_.pocket_receivers;
    const std::uint32_t mark = ++scratch_.pocket_count;
    queue.clear();
    receivers.clear();
    queue.emplace_back(k, 0);
    stamp[k] = mark;
    // breadth first through wet cells, the directions in their order: the same cells in the same order on
    // any thread count
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const auto [cell, steps] = queue[q];
        if (steps == pocket_reach_) continue;
        const auto [x, y, z] = coords(cell);
        for (int i = 1; i < Q; ++i) {
            const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
            if (n < 0) continue;
            const auto un = static_cast<std::size_t>(n);
            if (stamp[un] == mark) continue;
            const CellType t = type_[un];
            if (t != CellType::fluid && t != CellType::interface) continue;
            stamp[un] = mark;
            queue.emplace_back(static_cast<std::uint32_t>(un), steps + 1);
            if (t == CellType::interface) receivers.push_back(static_cast<std::uint32_t>(un));
        }
    }
    if (receivers.empty()) return false;
    const double share = deficit / static_cast<double>(receivers.size());
    // (a slab spreads the pockets of its ghost planes too, as it converts their cells; their counts are
    // their owner's)
    const bool own = !slab_.spread || own_plane(k);
    const bool counted = own && !region_.empty(), from_region = counted && in_region(k);
    for (const std::uint32_t n : receivers) {
        mass_[n] += share;
        // what crossed the region's face (the region's tally of the spreads, region_inflow()[2])
        if (counted && in_region(n) != from_region) region_inflow_[2] += from_region ? -share : share;
    }
    if (own) ++surface_stats_.pocket_cells;
    return true;
}

template void FluidLattice<float>::set_pocket_reach(int);
template void FluidLattice<double>::set_pocket_reach(int);
template bool FluidLattice<float>::spread_pocket(std::uint32_t, double);
template bool FluidLattice<double>::spread_pocket(std::uint32_t, double);

}  // namespace sabo::lbm
