// SPDX-License-Identifier: MIT
// Where a closed gas pocket's volume comes from (docs/lbm.md, "What the spread moves"): an enclosed
// interface cell fills whatever its mass, and its deficit is taken from the interface cells near it,
// reachable through the fluid, instead of from the whole surface.
#include <fmt/format.h>

#include <array>
#include <cstdint>

#include "core/error.h"
#include "lbm/fluid_lattice.h"

namespace sabo::lbm {

namespace {

constexpr int max_side = 2 * FluidLattice<double>::max_pocket_reach + 1;
constexpr std::size_t max_box_words = (max_side * max_side * max_side + 63) / 64;

}  // namespace

template <class Real>
void FluidLattice<Real>::set_pocket_reach(int cells) {
    if (cells < 0 || cells > max_pocket_reach)
        throw InputError(
            fmt::format("the pocket's reach {} cells is outside [0, {}]", cells, max_pocket_reach));
    pocket_reach_ = cells;
}

template <class Real>
void FluidLattice<Real>::find_pocket_receivers(std::uint32_t k, PocketSearch& search) const {
    // the cells seen are bits of the box of 2 reach + 1 cells a side around k, which along a periodic axis
    // shorter than that spans the axis (its bits the cells' own coordinates): each cell once, and no marks
    // in the lattice, so that every thread searches on its own
    const int reach = pocket_reach_, side = 2 * reach + 1;
    const std::array<int, 3> start = coords(k), cells = {shape_.nx, shape_.ny, shape_.nz};
    std::array<bool, 3> spans{};
    std::array<int, 3> size{};
    for (std::size_t a = 0; a < 3; ++a) {
        spans[a] = shape_.periodic[a] && cells[a] < side;
        size[a] = spans[a] ? cells[a] : side;
    }
    const auto bit = [&](const std::array<int, 3>& c) {
        int at = 0;
        for (int a = 2; a >= 0; --a) {
            const auto ua = static_cast<std::size_t>(a);
            int b = c[ua];
            if (!spans[ua]) {
                int offset = c[ua] - start[ua];
                if (shape_.periodic[ua] && offset > reach) offset -= cells[ua];
                if (shape_.periodic[ua] && offset < -reach) offset += cells[ua];
                b = offset + reach;
            }
            at = at * size[ua] + b;
        }
        return static_cast<std::size_t>(at);
    };
    std::array<std::uint64_t, max_box_words> seen;
    const auto box = static_cast<std::size_t>(size[0] * size[1] * size[2]);
    std::fill_n(seen.begin(), (box + 63) / 64, std::uint64_t{0});
    const auto mark = [&](std::size_t b) {  // false if seen before
        const std::uint64_t mask = std::uint64_t{1} << (b % 64);
        if ((seen[b / 64] & mask) != 0) return false;
        seen[b / 64] |= mask;
        return true;
    };
    const auto visit = [&](const std::array<int, 3>& c) { return mark(bit(c)); };
    auto& queue = search.queue;
    queue.clear();
    queue.push_back({k, start, 0});
    visit(start);
    bool inside = true;  // the box within the lattice: no edge, no wrap
    for (std::size_t a = 0; a < 3; ++a) inside = inside && start[a] >= reach && start[a] + reach < cells[a];
    if (inside) {  // (most pockets: a neighbour's index and bit are its cell's plus a constant)
        std::array<std::ptrdiff_t, Q> cell_step{};
        std::array<int, Q> bit_step{};
        for (int i = 1; i < Q; ++i) {
            cell_step[static_cast<std::size_t>(i)] =
                static_cast<std::ptrdiff_t>(index(1 + cx[i], 1 + cy[i], 1 + cz[i])) -
                static_cast<std::ptrdiff_t>(index(1, 1, 1));
            bit_step[static_cast<std::size_t>(i)] = cx[i] + side * (cy[i] + side * cz[i]);
        }
        for (std::size_t q = 0; q < queue.size(); ++q) {
            const PocketStep from = queue[q];
            if (from.steps == reach) continue;
            const auto from_bit = static_cast<int>(bit(from.at));
            for (std::size_t i = 1; i < Q; ++i) {
                const auto n =
                    static_cast<std::size_t>(static_cast<std::ptrdiff_t>(from.cell) + cell_step[i]);
                const CellType t = type_[n];
                if (t != CellType::fluid && t != CellType::interface) continue;
                if (!mark(static_cast<std::size_t>(from_bit + bit_step[i]))) continue;
                const int ii = static_cast<int>(i);
                queue.push_back({static_cast<std::uint32_t>(n),
                                 {from.at[0] + cx[ii], from.at[1] + cy[ii], from.at[2] + cz[ii]},
                                 from.steps + 1});
                if (t == CellType::interface) search.found.push_back(static_cast<std::uint32_t>(n));
            }
        }
        return;
    }
    // breadth first through wet cells, the directions in their order (the coordinates carried along: no
    // division per neighbour)
    const auto wrap = [&](int c, std::size_t a) {  // one step off an axis's end, back on it (periodic)
        return c < 0 ? c + cells[a] : (c >= cells[a] ? c - cells[a] : c);
    };
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const PocketStep from = queue[q];
        if (from.steps == reach) continue;
        const std::array<int, 3>& at = from.at;
        for (int i = 1; i < Q; ++i) {
            const std::ptrdiff_t n = neighbour(at[0], at[1], at[2], i, 1);
            if (n < 0) continue;
            const auto un = static_cast<std::size_t>(n);
            const CellType t = type_[un];
            if (t != CellType::fluid && t != CellType::interface) continue;
            const std::array<int, 3> next = {wrap(at[0] + cx[i], 0), wrap(at[1] + cy[i], 1),
                                             wrap(at[2] + cz[i], 2)};
            if (!visit(next)) continue;
            queue.push_back({static_cast<std::uint32_t>(un), next, from.steps + 1});
            if (t == CellType::interface) search.found.push_back(static_cast<std::uint32_t>(un));
        }
    }
}

template <class Real>
void FluidLattice<Real>::spread_pocket(std::uint32_t k, double deficit,
                                       std::span<const std::uint32_t> receivers) {
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
}

template void FluidLattice<float>::set_pocket_reach(int);
template void FluidLattice<double>::set_pocket_reach(int);
template void FluidLattice<float>::find_pocket_receivers(std::uint32_t, PocketSearch&) const;
template void FluidLattice<double>::find_pocket_receivers(std::uint32_t, PocketSearch&) const;
template void FluidLattice<float>::spread_pocket(std::uint32_t, double, std::span<const std::uint32_t>);
template void FluidLattice<double>::spread_pocket(std::uint32_t, double, std::span<const std::uint32_t>);

}  // namespace sabo::lbm
