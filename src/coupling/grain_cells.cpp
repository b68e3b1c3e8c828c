// SPDX-License-Identifier: MIT
#include "coupling/grain_cells.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace sabo::coupling {

void GrainCellFinder::find(const dem::Particles& p, const LatticeFrame& frame) {
    const std::size_t stored = frame.plane * static_cast<std::size_t>(frame.nz);
    if (owner_.size() != stored) {
        owner_.assign(stored, -1);
        depth_.assign(stored, 0.0);
        covered_.assign((stored + 63) / 64, 0);
    }
    const double inv_dx = 1.0 / frame.dx;
    const auto first = [&](double v, int n) {
        return std::clamp(static_cast<int>(std::ceil(v * inv_dx - 0.5)), 0, n);
    };
    const auto last = [&](double v, int n) {  // one past
        return std::clamp(static_cast<int>(std::floor(v * inv_dx - 0.5)) + 1, 0, n);
    };
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        const Vec3 rel = p.x[i] - frame.origin;
        const double r = p.r[i], r2 = r * r;
        const int x0 = first(rel.x - r, frame.nx), x1 = last(rel.x + r, frame.nx);
        const int y0 = first(rel.y - r, frame.ny), y1 = last(rel.y + r, frame.ny);
        const int z0 = first(rel.z - r, frame.nz), z1 = last(rel.z + r, frame.nz);
        for (int z = z0; z < z1; ++z)
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const double d2 = norm2(frame.centre(x, y, z) - p.x[i]);
                    if (d2 >= r2) continue;
                    const std::size_t k = static_cast<std::size_t>(x) +
                                          frame.row * static_cast<std::size_t>(y) +
                                          frame.plane * static_cast<std::size_t>(z);
                    const double depth = d2 / r2;
                    // grains come in ascending order: an equal depth keeps the lower index
                    if (owner_[k] >= 0 && depth >= depth_[k]) continue;
                    owner_[k] = static_cast<std::int32_t>(i);
                    depth_[k] = depth;
                    covered_[k / 64] |= std::uint64_t{1} << (k % 64);
                }
    }
    cells_.clear();
    for (std::size_t w = 0; w < covered_.size(); ++w) {
        for (std::uint64_t bits = covered_[w]; bits != 0; bits &= bits - 1) {
            const std::size_t k = 64 * w + static_cast<std::size_t>(std::countr_zero(bits));
            const std::size_t z = k / frame.plane, in_plane = k % frame.plane;
            const Vec3 c = frame.centre(static_cast<int>(in_plane % frame.row),
                                        static_cast<int>(in_plane / frame.row), static_cast<int>(z));
            cells_.push_back({k, static_cast<std::uint32_t>(owner_[k]), c});
            owner_[k] = -1;
        }
        covered_[w] = 0;
    }
}

}  // namespace sabo::coupling
