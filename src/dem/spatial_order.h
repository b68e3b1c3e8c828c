// SPDX-License-Identifier: MIT
// Spatial ordering of the mobile grains. As a flow mixes, grains that are neighbours in space end up
// far apart in index: pair loops then miss the caches, and with several threads most grains have
// owners in another thread's range (they are "parked": gathered after a barrier). Sorting the grains
// by cell from time to time restores the locality the initial lattice had. The order depends only
// on the positions, so results stay independent of the thread count.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace sabo::dem {

// New-to-old permutation of the first `n_mobile` points: ascending cell of a grid of edge `cell` over
// their bounding box, the cells in slabs of 4 across the box's longest extent, slab after slab, inside a
// slab z slowest and x fastest; ties by old index (dem/counting_sort.h, stable). start, histogram: scratch.
void spatial_order(const std::vector<Vec3>& x, std::size_t n_mobile, double cell,
                   std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& start,
                   std::vector<std::uint32_t>& histogram);

}  // namespace sabo::dem
