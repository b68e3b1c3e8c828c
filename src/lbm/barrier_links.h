// SPDX-License-Identifier: MIT
// The wall links into a barrier's obstacles (elements ≥ 1) kept one by one, for a load map finer than the
// barrier's elements: a mesh barrier's force per triangle (docs/geometry.md, "Force maps on the mesh").
// FluidLattice::keep_barrier_links() asks for them; the list follows the obstacles (relink()) and each step
// writes every listed link's momentum exchange (zero for a cell the step did not update).
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace sabo::lbm {

struct BarrierLinks {
    // per link, ascending by cell then direction: the stored index of the link's wet-side cell (one of the
    // slab's own planes), the direction c_i from it into the obstacle, and the obstacle's element
    std::vector<std::uint32_t> cell;
    std::vector<std::uint8_t> direction;
    std::vector<std::uint16_t> element;
    // the last step's momentum given to the obstacle along c_i, relative to the atmosphere (the link's
    // force is c_i · momentum, lattice units): the terms the element's force sums
    std::vector<double> momentum;
    // changes whenever the list does (a face move, a checkpoint read): what a caller's per-link data follows
    std::uint64_t version = 0;

    [[nodiscard]] std::size_t size() const { return cell.size(); }
    // The link of `cell` along `direction` (its index), or size() if not listed.
    [[nodiscard]] std::size_t find(std::uint32_t of_cell, int along) const {
        std::size_t j =
            static_cast<std::size_t>(std::lower_bound(cell.begin(), cell.end(), of_cell) - cell.begin());
        for (; j < cell.size() && cell[j] == of_cell; ++j)
            if (direction[j] == along) return j;
        return cell.size();
    }
};

}  // namespace sabo::lbm
