// SPDX-License-Identifier: MIT
#include "coupling/grain_cells.h"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace sabo::coupling {

std::size_t cell_centres_inside(const Vec3& x, double r, const LatticeFrame& frame) {
    const Vec3 rel = (x - frame.origin) / frame.dx;  // in cells; centres at integers + ½
    const double rc = r / frame.dx, rc2 = rc * rc;
    std::size_t count = 0;
    for (int k = static_cast<int>(std::ceil(rel.z - rc - 0.5));
         k <= static_cast<int>(std::floor(rel.z + rc - 0.5)); ++k)
        for (int j = static_cast<int>(std::ceil(rel.y - rc - 0.5));
             j <= static_cast<int>(std::floor(rel.y + rc - 0.5)); ++j)
            for (int i = static_cast<int>(std::ceil(rel.x - rc - 0.5));
                 i <= static_cast<int>(std::floor(rel.x + rc - 0.5)); ++i) {
                const Vec3 d{i + 0.5 - rel.x, j + 0.5 - rel.y, k + 0.5 - rel.z};
                if (norm2(d) < rc2) ++count;
            }
    return count;
}

void GrainCellFinder::find(std::span<const Vec3> centres, std::span<const double> radii,
                           const LatticeFrame& frame) {
    const std::size_t stored = frame.plane * static_cast<std::size_t>(frame.nz);
    const std::size_t plane_words = (frame.plane + 63) / 64;
    if (owner_.size() != stored) {
        owner_.assign(stored, -1);
        depth_.assign(stored, 0.0);
        covered_.assign(plane_words * static_cast<std::size_t>(frame.nz), 0);
    }
    const double inv_dx = 1.0 / frame.dx;
    const auto first = [&](double v, int n) {
        return std::clamp(static_cast<int>(std::ceil(v * inv_dx - 0.5)), 0, n);
    };
    const auto last = [&](double v, int n) {  // one past
        return std::clamp(static_cast<int>(std::floor(v * inv_dx - 0.5)) + 1, 0, n);
    };
    const std::size_t n = centres.size();
    const int threads = n > 512 ? omp_get_max_threads() : 1;
    if (offset_.size() < static_cast<std::size_t>(threads) + 1)
        offset_.resize(static_cast<std::size_t>(threads) + 1);
        // Each thread its own slab of planes (and of the bitmap, whose words do not straddle planes): every
        // grain reaching into the slab marks its cells there, in ascending grain order, so a cell's owner is
        // the same whoever marks it; then the slab's cells, counted, go in ascending order to their place in
        // cells_.
#pragma omp parallel num_threads(threads)
    {
        const int team = omp_get_num_threads(), t = omp_get_thread_num();
        const int slab_begin = frame.nz * t / team, slab_end = frame.nz * (t + 1) / team;
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 rel = centres[i] - frame.origin;
            const double r = radii[i], r2 = r * r;
            const int z0 = std::max(first(rel.z - r, frame.nz), slab_begin);
            const int z1 = std::min(last(rel.z + r, frame.nz), slab_end);
            if (z0 >= z1) continue;
            const int x0 = first(rel.x - r, frame.nx), x1 = last(rel.x + r, frame.nx);
            const int y0 = first(rel.y - r, frame.ny), y1 = last(rel.y + r, frame.ny);
            for (int z = z0; z < z1; ++z)
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) {
                        const double d2 = norm2(frame.centre(x, y, z) - centres[i]);
                        if (d2 >= r2) continue;
                        const std::size_t in_plane =
                            static_cast<std::size_t>(x) + frame.row * static_cast<std::size_t>(y);
                        const std::size_t k = in_plane + frame.plane * static_cast<std::size_t>(z);
                        const double depth = d2 / r2;
                        // grains come in ascending order: an equal depth keeps the lower index
                        if (owner_[k] >= 0 && depth >= depth_[k]) continue;
                        owner_[k] = static_cast<std::int32_t>(i);
                        depth_[k] = depth;
                        covered_[plane_words * static_cast<std::size_t>(z) + in_plane / 64] |=
                            std::uint64_t{1} << (in_plane % 64);
                    }
        }
        std::uint64_t* const slab = covered_.data() + plane_words * static_cast<std::size_t>(slab_begin);
        const std::size_t slab_words = plane_words * static_cast<std::size_t>(slab_end - slab_begin);
        std::size_t count = 0;
        for (std::size_t w = 0; w < slab_words; ++w)
            count += static_cast<std::size_t>(std::popcount(slab[w]));
        offset_[static_cast<std::size_t>(t) + 1] = count;
#pragma omp barrier
#pragma omp single
        {
            offset_[0] = 0;
            for (int u = 0; u < team; ++u)
                offset_[static_cast<std::size_t>(u) + 1] += offset_[static_cast<std::size_t>(u)];
            cells_.resize(offset_[static_cast<std::size_t>(team)]);
        }
        std::size_t at = offset_[static_cast<std::size_t>(t)];
        for (std::size_t w = 0; w < slab_words; ++w) {
            for (std::uint64_t bits = slab[w]; bits != 0; bits &= bits - 1) {
                const std::size_t z = static_cast<std::size_t>(slab_begin) + w / plane_words;
                const std::size_t in_plane =
                    64 * (w % plane_words) + static_cast<std::size_t>(std::countr_zero(bits));
                const std::size_t k = in_plane + frame.plane * z;
                cells_[at++] = {k, static_cast<std::uint32_t>(owner_[k]),
                                frame.centre(static_cast<int>(in_plane % frame.row),
                                             static_cast<int>(in_plane / frame.row), static_cast<int>(z))};
                owner_[k] = -1;
            }
            slab[w] = 0;
        }
    }
}

}  // namespace sabo::coupling
