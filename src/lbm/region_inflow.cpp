// SPDX-License-Identifier: MIT
// What enters a lattice's region (FluidLattice::set_region; docs/analysis.md, "Overflow"): the links into it,
// counted after each sweep, and what the free surface's conversions hand it. Kept out of free_surface.cpp:
// added to its loops this code changed what the compiler inlined there (surface_normal's neighbour lookups
// went out of line: the fluid-only debris run 4-7 % slower).
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "lbm/fluid_lattice.h"

namespace sabo::lbm {

template <class Real>
void FluidLattice<Real>::set_region(std::vector<std::uint8_t> bits) {
    if (!bits.empty() && bits.size() != n_)
        throw std::logic_error("FluidLattice::set_region: one byte per stored cell");
    region_ = std::move(bits);
    crossings_.clear();
    if (region_.empty()) return;
    // the links from the own planes' cells outside the region into it, each once
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y)
            for (int x = slab_.own_begin; x < slab_.own_end; ++x) {
                const std::size_t k = index(x, y, z);
                if (in_region(k)) continue;
                const auto part = static_cast<std::uint8_t>((region_[k] & region_above_crest) != 0 ? 0 : 1);
                for (int i = 1; i < Q; ++i) {
                    const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
                    if (n >= 0 && in_region(static_cast<std::size_t>(n)))
                        crossings_.push_back(
                            {k, static_cast<std::size_t>(n), static_cast<std::uint8_t>(i), part});
                }
            }
}

template <class Real>
void FluidLattice<Real>::count_crossings() {
    const auto wet = [](CellType t) { return t == CellType::fluid || t == CellType::interface; };
    for (const Crossing& c : crossings_) {
        const CellType from = type_[c.from], to = type_[c.to];
        if (!wet(from) || !wet(to)) continue;  // gas and obstacles exchange nothing
        double alpha = 1.0;                    // (two interface cells: the mean of their fill fractions)
        if (from == CellType::interface && to == CellType::interface)
            alpha = 0.5 * (static_cast<double>(fill_[c.from]) + static_cast<double>(fill_[c.to]));
        const int i = c.direction;
        region_inflow_[c.part] +=
            alpha * (streamed_in(c.to, i, c.from) - streamed_in(c.from, opposite(i), c.to));
    }
}

template <class Real>
double FluidLattice<Real>::region_orphan_excess(std::span<const OrphanMass> orphans) const {
    double excess = 0.0;
    for (const OrphanMass& o : orphans) {
        const auto [x, y, z] = o.cell();
        if (in_region(index(x - slab_.first_global_x, y, z))) excess += o.mass;
    }
    return excess;
}

template <class Real>
void FluidLattice<Real>::count_region_conversions(double share, double region_orphans) {
    // the shares handed across the region's face (a converted cell's to its interface neighbours; a
    // slab's: its own cells')
    const auto& filled = scratch_.filled;
    const auto& emptied = scratch_.emptied;
    const std::size_t nf = filled.size(), converted = nf + emptied.size();
    for (std::size_t c = 0; c < converted; ++c) {
        const std::uint32_t k = c < nf ? filled[c] : emptied[c - nf];
        if (slab_.spread && !own_plane(k)) continue;
        const std::int64_t* to = scratch_.share_to.data() + c * (Q - 1);
        const double* mass = scratch_.share_mass.data() + c * (Q - 1);
        for (int i = 0; i < Q - 1; ++i)
            if (to[i] >= 0 && in_region(static_cast<std::size_t>(to[i])) != in_region(k))
                region_inflow_[2] += in_region(k) ? -mass[i] : mass[i];
    }
    // the spread's shares in the region's own interface cells, less the region's own orphans
    if (share == 0.0) return;
    std::size_t cells = 0;
    for (const std::uint32_t k : interface_) cells += in_region(k) && (!slab_.spread || own_plane(k)) ? 1 : 0;
    region_inflow_[2] += share * static_cast<double>(cells) - region_orphans;
}

template void FluidLattice<float>::set_region(std::vector<std::uint8_t>);
template void FluidLattice<double>::set_region(std::vector<std::uint8_t>);
template void FluidLattice<float>::count_crossings();
template void FluidLattice<double>::count_crossings();
template double FluidLattice<float>::region_orphan_excess(std::span<const OrphanMass>) const;
template double FluidLattice<double>::region_orphan_excess(std::span<const OrphanMass>) const;
template void FluidLattice<float>::count_region_conversions(double, double);
template void FluidLattice<double>::count_region_conversions(double, double);

}  // namespace sabo::lbm
