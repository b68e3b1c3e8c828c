// SPDX-License-Identifier: MIT
#include "coupling/grain_cells.h"

#include <algorithm>
#include <cmath>

namespace sabo::coupling {

void GrainCellFinder::find(const dem::Particles& p, const LatticeFrame& frame) {
    // every (cell, grain) pair with the centre inside, then sorted by cell and, per cell, by depth: the
    // first of each cell wins. The candidates' order before the sort does not matter (the key is total).
    auto& candidates = candidates_;
    candidates.clear();
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
                    const Vec3 c = frame.centre(x, y, z);
                    const double d2 = norm2(c - p.x[i]);
                    if (d2 >= r2) continue;
                    const std::size_t k = static_cast<std::size_t>(x) +
                                          frame.row * static_cast<std::size_t>(y) +
                                          frame.plane * static_cast<std::size_t>(z);
                    candidates.push_back({d2 / r2, {k, static_cast<std::uint32_t>(i), c}});
                }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        if (a.c.cell != b.c.cell) return a.c.cell < b.c.cell;
        if (a.depth != b.depth) return a.depth < b.depth;
        return a.c.grain < b.c.grain;
    });
    cells_.clear();
    for (const Candidate& r : candidates)
        if (cells_.empty() || cells_.back().cell != r.c.cell) cells_.push_back(r.c);
}

}  // namespace sabo::coupling
