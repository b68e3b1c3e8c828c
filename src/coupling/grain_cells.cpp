// SPDX-License-Identifier: MIT
#include "coupling/grain_cells.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>

namespace sabo::coupling {

namespace {

constexpr double half_diagonal = 0.86602540378443865;  // √3/2: a cell's centre to its corners, in cells

// The columns of solid_fraction(), relative to the cell's centre: x at the 89 strips' middles in order, y
// the same stepped by 55 (mod 89)
constexpr int fibonacci_columns = 89;
constexpr auto column_offsets(bool y) {
    std::array<double, fibonacci_columns> at{};
    for (int c = 0; c < fibonacci_columns; ++c)
        at[static_cast<std::size_t>(c)] =
            ((y ? c * 55 % fibonacci_columns : c) + 0.5) / fibonacci_columns - 0.5;
    return at;
}
constexpr auto column_x = column_offsets(false);
constexpr auto column_y = column_offsets(true);

// How far from a grain's centre the centres of the cells it covers may lie, m.
double reach(double r, double dx, CoverRule rule) {
    return rule == CoverRule::psm ? r + half_diagonal * dx : r;
}

}  // namespace

double solid_fraction(const Vec3& d, double rc) {
    const double distance = norm(d);
    if (distance + half_diagonal <= rc) return 1.0;
    if (distance - half_diagonal >= rc) return 0.0;
    // columns on a Fibonacci lattice (89 points, 55 apart): every x and every y of the cell's 89 strips
    // once, so a face of the sphere across the cell is resolved to 1/89 whatever its direction; written
    // branch-free (a column that misses the sphere has h = 0 and adds nothing) so that it vectorises
    const double rc2 = rc * rc;
    double length = 0.0;
#pragma omp simd reduction(+ : length)
    for (int c = 0; c < fibonacci_columns; ++c) {
        const double x = d.x + column_x[c], y = d.y + column_y[c];
        const double h = std::sqrt(std::max(rc2 - x * x - y * y, 0.0));  // the sphere spans z in [−h, h]
        length += std::max(0.0, std::min(d.z + 0.5, h) - std::max(d.z - 0.5, -h));
    }
    return std::min(1.0, length / fibonacci_columns);  // 89 lengths of at most 1 may round above 1
}

double cells_covered_alone(const Vec3& x, double r, const LatticeFrame& frame, CoverRule rule) {
    // the solid fractions of a sphere's cells add up to its volume (within 0.05 % at d/Δx ≈ 8): the volume
    // itself, and no second pass over its cut cells every step
    if (rule == CoverRule::psm)
        return 4.0 / 3.0 * std::numbers::pi * r * r * r / (frame.dx * frame.dx * frame.dx);
    const Vec3 rel = (x - frame.origin) / frame.dx;  // in cells; centres at integers + ½
    const double rc = r / frame.dx, rc2 = rc * rc;
    double inside = 0.0;
    for (int k = static_cast<int>(std::ceil(rel.z - rc - 0.5));
         k <= static_cast<int>(std::floor(rel.z + rc - 0.5)); ++k)
        for (int j = static_cast<int>(std::ceil(rel.y - rc - 0.5));
             j <= static_cast<int>(std::floor(rel.y + rc - 0.5)); ++j)
            for (int i = static_cast<int>(std::ceil(rel.x - rc - 0.5));
                 i <= static_cast<int>(std::floor(rel.x + rc - 0.5)); ++i) {
                const Vec3 d{i + 0.5 - rel.x, j + 0.5 - rel.y, k + 0.5 - rel.z};
                if (norm2(d) < rc2) inside += 1.0;
            }
    return inside;
}

void GrainCellFinder::find(std::span<const Vec3> centres, std::span<const double> radii,
                           const LatticeFrame& frame, CoverRule rule) {
    const std::size_t stored = frame.plane * static_cast<std::size_t>(frame.nz);
    const std::size_t plane_words = (frame.plane + 63) / 64;
    if (owner_.size() != stored) {
        owner_.assign(stored, -1);
        depth_.assign(stored, 0.0);
        covered_.assign(plane_words * static_cast<std::size_t>(frame.nz), 0);
    }
    const bool partial = rule == CoverRule::psm;
    if (partial && fraction_.size() != stored) fraction_.assign(stored, 0.0);
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
    // the cells of the grains' boxes below each plane (the grains may fill a few planes of many: the
    // threads' slabs are cut where they hold equal shares of the boxes, not of the planes)
    boxes_below_.assign(static_cast<std::size_t>(frame.nz) + 1, 0);
    if (threads > 1) {
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 rel = centres[i] - frame.origin;
            const double out = reach(radii[i], frame.dx, rule);
            const auto across =
                static_cast<std::uint64_t>((last(rel.x + out, frame.nx) - first(rel.x - out, frame.nx)) *
                                           (last(rel.y + out, frame.ny) - first(rel.y - out, frame.ny)));
            for (int z = first(rel.z - out, frame.nz); z < last(rel.z + out, frame.nz); ++z)
                boxes_below_[static_cast<std::size_t>(z) + 1] += across;
        }
        for (std::size_t z = 1; z < boxes_below_.size(); ++z) boxes_below_[z] += boxes_below_[z - 1];
    }
    // Each thread its own slab of planes (and of the bitmap, whose words do not straddle planes): every
    // grain reaching into the slab marks its cells there, in ascending grain order, so a cell's owner is
    // the same whoever marks it; then the slab's cells, counted, go in ascending order to their place in
    // cells_.
#pragma omp parallel num_threads(threads)
    {
        const int team = omp_get_num_threads(), t = omp_get_thread_num();
        const std::uint64_t total = boxes_below_.back();
        const auto cut = [&](int u) {  // the first plane of thread u's slab
            if (u <= 0) return 0;
            if (u >= team) return frame.nz;
            if (total == 0) return frame.nz * u / team;
            const std::uint64_t share =
                total * static_cast<std::uint64_t>(u) / static_cast<std::uint64_t>(team);
            return static_cast<int>(std::lower_bound(boxes_below_.begin(), boxes_below_.end(), share) -
                                    boxes_below_.begin());
        };
        const int slab_begin = std::min(cut(t), frame.nz),
                  slab_end = std::max(slab_begin, std::min(cut(t + 1), frame.nz));
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 rel = centres[i] - frame.origin;
            const double r = radii[i], r2 = r * r;
            const double out = reach(r, frame.dx, rule), out2 = out * out;
            const int z0 = std::max(first(rel.z - out, frame.nz), slab_begin);
            const int z1 = std::min(last(rel.z + out, frame.nz), slab_end);
            if (z0 >= z1) continue;
            const int x0 = first(rel.x - out, frame.nx), x1 = last(rel.x + out, frame.nx);
            const int y0 = first(rel.y - out, frame.ny), y1 = last(rel.y + out, frame.ny);
            for (int z = z0; z < z1; ++z)
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) {
                        const Vec3 d = frame.centre(x, y, z) - centres[i];
                        const double d2 = norm2(d);
                        if (d2 >= out2) continue;
                        const double fraction = partial ? solid_fraction(d * inv_dx, r * inv_dx) : 1.0;
                        if (fraction <= 0.0) continue;
                        const std::size_t in_plane =
                            static_cast<std::size_t>(x) + frame.row * static_cast<std::size_t>(y);
                        const std::size_t k = in_plane + frame.plane * static_cast<std::size_t>(z);
                        const double depth = d2 / r2;
                        // grains come in ascending order: an equal claim keeps the lower index
                        if (owner_[k] >= 0) {
                            const bool more = partial && fraction > fraction_[k];
                            const bool as_much = !partial || fraction == fraction_[k];
                            if (!more && !(as_much && depth < depth_[k])) continue;
                        }
                        owner_[k] = static_cast<std::int32_t>(i);
                        depth_[k] = depth;
                        if (partial) fraction_[k] = fraction;
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
                                             static_cast<int>(in_plane / frame.row), static_cast<int>(z)),
                                partial ? fraction_[k] : 1.0};
                owner_[k] = -1;
            }
            slab[w] = 0;
        }
    }
}

}  // namespace sabo::coupling
