// SPDX-License-Identifier: MIT
#include "dem/spatial_order.h"

#include <algorithm>
#include <cmath>

namespace sabo::dem {

void spatial_order(const std::vector<Vec3>& x, std::size_t n_mobile, double cell,
                   std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& scratch) {
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (std::size_t i = 0; i < n_mobile; ++i) {
        lo = {std::min(lo.x, x[i].x), std::min(lo.y, x[i].y), std::min(lo.z, x[i].z)};
        hi = {std::max(hi.x, x[i].x), std::max(hi.y, x[i].y), std::max(hi.z, x[i].z)};
    }
    // at most ~4 cells per grain: sparse flows get coarser cells (the order only needs locality)
    const Vec3 ext = hi - lo;
    auto cells_along = [&](double e) { return static_cast<std::size_t>(std::floor(e / cell)) + 1; };
    while (static_cast<double>(cells_along(ext.x)) * static_cast<double>(cells_along(ext.y)) *
               static_cast<double>(cells_along(ext.z)) >
           4.0 * static_cast<double>(n_mobile) + 64.0) {
        cell *= 1.25;
    }
    const std::size_t nx = cells_along(ext.x), ny = cells_along(ext.y), nz = cells_along(ext.z);
    auto key = [&](const Vec3& p) {
        const auto c = [&](double v, double l, std::size_t n) {
            return std::min(n - 1, static_cast<std::size_t>(std::max(0.0, std::floor((v - l) / cell))));
        };
        return (c(p.z, lo.z, nz) * ny + c(p.y, lo.y, ny)) * nx + c(p.x, lo.x, nx);
    };
    scratch.assign(nx * ny * nz + 1, 0);
    for (std::size_t i = 0; i < n_mobile; ++i) ++scratch[key(x[i]) + 1];
    for (std::size_t c = 1; c < scratch.size(); ++c) scratch[c] += scratch[c - 1];
    order.resize(n_mobile);
    for (std::size_t i = 0; i < n_mobile; ++i) order[scratch[key(x[i])]++] = static_cast<std::uint32_t>(i);
}

}  // namespace sabo::dem
