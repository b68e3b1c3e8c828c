// SPDX-License-Identifier: MIT
#include "dem/neighbor_list.h"

#include <algorithm>
#include <cmath>

#include "dem/counting_sort.h"
#include "dem/mesh_contacts.h"
#include "dem/particles.h"

namespace sabo::dem {

namespace {

// A wall's entries in a grain's row: a mesh's one per contact slot, another wall's one.
std::uint32_t entries_of(const Wall& w) {
    return w.shape == WallShape::mesh ? mesh_slots : 1;
}

struct Grid {
    Vec3 lo{};
    double inv_cell = 1.0;
    int n[3] = {1, 1, 1};

    [[nodiscard]] int coord(double v, double lo_k, int n_k) const {
        const int c = static_cast<int>(std::floor((v - lo_k) * inv_cell));
        return std::clamp(c, 0, n_k - 1);
    }
    [[nodiscard]] std::uint32_t index(int cx, int cy, int cz) const {
        return static_cast<std::uint32_t>((cz * n[1] + cy) * n[0] + cx);
    }
};

// Turns per-grain counts (offset[i + 1]) into CSR offsets and copies each grain's staging row
// (`capacity` entries apart) into the compact array `out`.
template <class T>
void compact_rows(const std::vector<T>& stage, std::size_t capacity, std::vector<std::uint32_t>& offset,
                  std::vector<T>& out) {
    const std::size_t rows = offset.size() - 1;
    for (std::size_t i = 0; i < rows; ++i) offset[i + 1] += offset[i];
    out.resize(offset[rows]);
    const auto n = static_cast<std::ptrdiff_t>(rows);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const T* row = stage.data() + static_cast<std::size_t>(i) * capacity;
        std::copy(row, row + (offset[i + 1] - offset[i]), out.begin() + offset[i]);
    }
}

}  // namespace

namespace {

// offsets of a CSR list: `rows` + 1 of them, from 0, never decreasing, ending at the list's length
bool valid_offsets(const std::vector<std::uint32_t>& offset, std::size_t rows, std::size_t length) {
    if (offset.size() != rows + 1 || offset.front() != 0 || offset.back() != length) return false;
    return std::is_sorted(offset.begin(), offset.end());
}

template <class Range>
bool all_below(const Range& v, std::size_t limit) {
    return std::all_of(v.begin(), v.end(), [&](auto e) { return static_cast<std::size_t>(e) < limit; });
}

}  // namespace

bool NeighborList::consistent(std::size_t n, std::size_t n_mobile, const std::vector<Wall>& walls) const {
    const std::size_t np = partner_.size();
    if (builds_ == 0) return offset_.size() <= 1 && np == 0;  // never built: built at the first step
    if (!valid_offsets(offset_, n_mobile, np) || !valid_offsets(t_offset_, n, np) ||
        !valid_offsets(wall_offset_, n_mobile, wall_.size()) ||
        !valid_offsets(wall_triangle_offset_, wall_.size(), wall_triangle_.size()) ||
        at_build_.size() != n_mobile || owner_.size() != np || t_slot_.size() != np ||
        first_owner_.size() != n)
        return false;
    for (std::size_t i = 0; i < n_mobile; ++i)
        for (auto k = offset_[i]; k < offset_[i + 1]; ++k)
            if (owner_[k] != i || partner_[k] <= i || partner_[k] >= n) return false;
    if (!all_below(wall_, walls.size())) return false;
    // a mesh wall's entries as its slots in a row within one grain's, the first with its triangles; the
    // other walls' with none
    for (std::size_t i = 0; i < n_mobile; ++i) {
        for (std::uint32_t k = wall_offset_[i]; k < wall_offset_[i + 1];) {
            const Wall& w = walls[wall_[k]];
            const std::uint32_t group = entries_of(w);
            if (k + group > wall_offset_[i + 1]) return false;
            for (std::uint32_t s = 0; s < group; ++s) {
                const auto t = triangles(k + s);
                if (wall_[k + s] != wall_[k] ||
                    (s > 0 || w.shape != WallShape::mesh ? !t.empty()
                                                         : !all_below(t, w.surface->mesh->triangles.size())))
                    return false;
            }
            k += group;
        }
    }
    return all_below(t_slot_, np) &&
           std::all_of(first_owner_.begin(), first_owner_.end(),
                       [&](std::uint32_t i) { return i == no_owner || i < n_mobile; });
}

std::size_t NeighborList::bytes() const {
    return at_build_.capacity() * sizeof(AtBuild) +
           (offset_.capacity() + partner_.capacity() + owner_.capacity() + t_offset_.capacity() +
            t_slot_.capacity() + first_owner_.capacity() + wall_offset_.capacity() +
            wall_triangle_offset_.capacity() + wall_triangle_.capacity() + triangle_count_.capacity() +
            cell_of_.capacity() + cell_start_.capacity() + cell_items_.capacity() + stage_.capacity() +
            histogram_.capacity()) *
               sizeof(std::uint32_t) +
           wall_.capacity() * sizeof(std::uint16_t) + chunk_bytes() +
           cell_entry_.capacity() * sizeof(CellEntry);
}

std::size_t NeighborList::chunk_bytes() const {
    std::size_t bytes = wall_chunks_.capacity() * sizeof(WallChunk);
    for (const WallChunk& c : wall_chunks_)
        bytes += c.wall.capacity() * sizeof(std::uint16_t) +
                 (c.triangle_offset.capacity() + c.triangles.capacity()) * sizeof(std::uint32_t);
    return bytes;
}

bool NeighborList::needs_rebuild(const Particles& p) const {
    if (builds_ == 0) return true;
    const auto n = static_cast<std::ptrdiff_t>(p.n_mobile);
    int exceeded = 0;
#pragma omp parallel for schedule(static) reduction(| : exceeded)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        if (excess(static_cast<std::size_t>(i), p.x[i]) > 0.0) exceeded = 1;
    }
    return exceeded != 0;
}

void NeighborList::build(const Particles& p, const std::vector<Wall>& walls,
                         std::span<const double> half_skin, double fixed_half_skin, std::size_t rows) {
    ++builds_;
    const std::size_t n = p.size();
    const std::size_t nm = p.n_mobile;
    at_build_.resize(nm);
    const auto sn = static_cast<std::ptrdiff_t>(n);
    const auto reach_of = [&](std::size_t i) { return p.r[i] + (i < nm ? half_skin[i] : fixed_half_skin); };

    // --- linked cells over the bounding box of all particles (min/max reductions are exact)
    Grid g;
    double lo_x = 1e300, lo_y = 1e300, lo_z = 1e300, hi_x = -1e300, hi_y = -1e300, hi_z = -1e300;
    double reach_max = 0.0;
    // clang-format off
#pragma omp parallel for schedule(static) reduction(min : lo_x, lo_y, lo_z) reduction(max : hi_x, hi_y, hi_z, reach_max)
    // clang-format on
    for (std::ptrdiff_t i = 0; i < sn; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const Vec3 xi = p.x[i];
        if (ui < nm) at_build_[ui] = {xi, half_skin[ui] * half_skin[ui]};
        lo_x = std::min(lo_x, xi.x);
        lo_y = std::min(lo_y, xi.y);
        lo_z = std::min(lo_z, xi.z);
        hi_x = std::max(hi_x, xi.x);
        hi_y = std::max(hi_y, xi.y);
        hi_z = std::max(hi_z, xi.z);
        reach_max = std::max(reach_max, reach_of(ui));
    }
    if (n == 0) {  // no particle (a rank of a divided run may hold none): one empty cell
        lo_x = lo_y = lo_z = hi_x = hi_y = hi_z = 0.0;
        reach_max = 1.0;
    }
    const Vec3 lo{lo_x, lo_y, lo_z}, hi{hi_x, hi_y, hi_z};
    double cell = 2.0 * reach_max;
    // Sparse domains: enlarge cells so the grid never has more than ~8 cells per particle.
    const Vec3 ext = hi - lo;
    const double max_cells = 8.0 * static_cast<double>(n) + 64.0;
    while ((std::floor(ext.x / cell) + 1) * (std::floor(ext.y / cell) + 1) * (std::floor(ext.z / cell) + 1) >
           max_cells) {
        cell *= 1.25;
    }
    g.lo = lo;
    g.inv_cell = 1.0 / cell;
    g.n[0] = static_cast<int>(std::floor(ext.x / cell)) + 1;
    g.n[1] = static_cast<int>(std::floor(ext.y / cell)) + 1;
    g.n[2] = static_cast<int>(std::floor(ext.z / cell)) + 1;
    const std::size_t n_cells = static_cast<std::size_t>(g.n[0]) * g.n[1] * g.n[2];

    cell_of_.resize(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < sn; ++i) {
        cell_of_[i] = g.index(g.coord(p.x[i].x, lo.x, g.n[0]), g.coord(p.x[i].y, lo.y, g.n[1]),
                              g.coord(p.x[i].z, lo.z, g.n[2]));
    }
    cell_items_.resize(n);
    counting_sort(
        n, n_cells, [&](std::size_t i) { return cell_of_[i]; }, cell_start_, histogram_,
        [&](std::size_t i, std::uint32_t at) { cell_items_[at] = static_cast<std::uint32_t>(i); });
    cell_entry_.resize(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t s = 0; s < sn; ++s) {
        const auto i = cell_items_[s];
        cell_entry_[s] = {p.x[i].x, p.x[i].y, p.x[i].z, reach_of(i)};
    }

    // --- half list: candidates j > i within reach, staged per grain, then compacted to CSR
    auto for_candidates = [&](std::size_t i, auto&& visit) {
        const Vec3 xi = p.x[i];
        const int cx = g.coord(xi.x, lo.x, g.n[0]), cy = g.coord(xi.y, lo.y, g.n[1]),
                  cz = g.coord(xi.z, lo.z, g.n[2]);
        const double reach_i = reach_of(i);
        // the three cells of a row along x are consecutive in cell order: one run per (y, z)
        const int x_lo = std::max(cx - 1, 0), x_hi = std::min(cx + 1, g.n[0] - 1);
        for (int z = std::max(cz - 1, 0); z <= std::min(cz + 1, g.n[2] - 1); ++z) {
            for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, g.n[1] - 1); ++y) {
                const auto s_end = cell_start_[g.index(x_hi, y, z) + 1];
                for (auto s = cell_start_[g.index(x_lo, y, z)]; s < s_end; ++s) {
                    const CellEntry& q = cell_entry_[s];
                    const double reach = reach_i + q.reach;
                    const double dx = q.x - xi.x, dy = q.y - xi.y, dz = q.z - xi.z;
                    const auto j = cell_items_[s];
                    // branch-free: about half the candidates pass, unpredictably
                    visit(j, (j > i) & (dx * dx + dy * dy + dz * dz < reach * reach));
                }
            }
        }
    };
    // One distance pass: candidates go to a fixed-capacity staging row per grain (the capacity
    // grows and the pass repeats in the rare case a row overflows), then rows are compacted. Every
    // candidate is written (branch-free) and kept only if it passes; a row has one spare slot
    // past its capacity that takes the writes of an overflowing row.
    offset_.assign(nm + 1, 0);
    const auto snm = static_cast<std::ptrdiff_t>(nm);
    while (true) {
        const std::size_t stride = stage_capacity_ + 1;
        stage_.resize(nm * stride);
        int overflow = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(max : overflow)
        for (std::ptrdiff_t i = 0; i < snm; ++i) {
            std::uint32_t* row = stage_.data() + static_cast<std::size_t>(i) * stride;
            std::uint32_t count = 0;
            if (static_cast<std::size_t>(i) >= rows) {
                offset_[i + 1] = 0;
                continue;
            }
            for_candidates(static_cast<std::size_t>(i), [&](std::uint32_t j, bool keep) {
                row[std::min(count, stage_capacity_)] = j;
                count += keep ? 1U : 0U;
            });
            if (count > stage_capacity_) overflow = std::max<int>(overflow, static_cast<int>(count));
            offset_[i + 1] = count;
            std::sort(row, row + std::min<std::uint32_t>(count, stage_capacity_));
        }
        if (overflow == 0) break;
        stage_capacity_ = static_cast<std::uint32_t>(overflow) + 8;
    }
    compact_rows(stage_, stage_capacity_ + 1, offset_, partner_);
    owner_.resize(partner_.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < snm; ++i) {
        std::fill(owner_.begin() + offset_[i], owner_.begin() + offset_[i + 1],
                  static_cast<std::uint32_t>(i));
    }

    // --- transposed index, ascending i for each partner (counting sort over k); the first slot of each
    // partner belongs to its smallest owner
    t_slot_.resize(partner_.size());
    first_owner_.assign(n, no_owner);
    counting_sort(
        partner_.size(), n, [&](std::size_t k) { return partner_[k]; }, t_offset_, histogram_,
        [&](std::size_t k, std::uint32_t at) {
            t_slot_[k] = at;
            if (at == t_offset_[partner_[k]]) first_owner_[partner_[k]] = owner_[k];
        });

    // --- wall candidates: walls whose surface is within 2 h_i of the sphere and, of a mesh wall, its
    // triangles within that reach.
    const std::size_t nw = walls.size();
    wall_offset_.assign(nm + 1, 0);
    triangle_count_.assign(nm + 1, 0);
    // calls candidate(w, triangles) for each wall candidate of grain i (triangles: a mesh's, else empty)
    const auto for_wall_candidates = [&](std::size_t i, std::vector<std::uint32_t>& triangles,
                                         auto&& candidate) {
        if (i >= rows) return;
        const double reach = 2.0 * half_skin[i];
        for (std::size_t w = 0; w < nw; ++w) {
            if (walls[w].shape == WallShape::mesh) {
                triangles_within(walls[w], p.x[i], p.r[i] + reach, triangles);
                if (!triangles.empty()) candidate(w, triangles);
            } else if (clearance(walls[w], {}, p.x[i], p.r[i]) < reach) {
                triangles.clear();
                candidate(w, triangles);
            }
        }
    };
    // one pass in chunks of grains, each chunk's entries into its own buffers, then copied in chunk order
    constexpr std::size_t chunk = 256;
    const std::size_t chunks = (nm + chunk - 1) / chunk;
    if (wall_chunks_.size() < chunks) wall_chunks_.resize(chunks);
    const auto schunks = static_cast<std::ptrdiff_t>(chunks);
#pragma omp parallel
    {
        std::vector<std::uint32_t> triangles;  // a thread's scratch
#pragma omp for schedule(dynamic, 1)
        for (std::ptrdiff_t c = 0; c < schunks; ++c) {
            WallChunk& out = wall_chunks_[static_cast<std::size_t>(c)];
            out.wall.clear();
            out.triangle_offset.clear();
            out.triangles.clear();
            const std::size_t first = static_cast<std::size_t>(c) * chunk, last = std::min(nm, first + chunk);
            for (std::size_t i = first; i < last; ++i) {
                const std::size_t walls_before = out.wall.size(), triangles_before = out.triangles.size();
                for_wall_candidates(i, triangles, [&](std::size_t w, const std::vector<std::uint32_t>& t) {
                    // a mesh's slots: the first holds the triangles, the others none
                    for (std::uint32_t slot = 0; slot < entries_of(walls[w]); ++slot) {
                        out.wall.push_back(static_cast<std::uint16_t>(w));
                        out.triangle_offset.push_back(static_cast<std::uint32_t>(out.triangles.size()));
                        if (slot == 0) out.triangles.insert(out.triangles.end(), t.begin(), t.end());
                    }
                });
                wall_offset_[i + 1] = static_cast<std::uint32_t>(out.wall.size() - walls_before);
                triangle_count_[i + 1] = static_cast<std::uint32_t>(out.triangles.size() - triangles_before);
            }
        }
    }
    for (std::size_t i = 0; i < nm; ++i) {
        wall_offset_[i + 1] += wall_offset_[i];
        triangle_count_[i + 1] += triangle_count_[i];
    }
    wall_.resize(wall_offset_[nm]);
    wall_triangle_offset_.resize(wall_.size() + 1);
    wall_triangle_offset_.back() = triangle_count_[nm];
    wall_triangle_.resize(triangle_count_[nm]);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t c = 0; c < schunks; ++c) {
        const WallChunk& in = wall_chunks_[static_cast<std::size_t>(c)];
        const std::size_t first = static_cast<std::size_t>(c) * chunk;
        const std::uint32_t k0 = wall_offset_[first], t0 = triangle_count_[first];
        std::copy(in.wall.begin(), in.wall.end(), wall_.begin() + k0);
        for (std::size_t e = 0; e < in.triangle_offset.size(); ++e)
            wall_triangle_offset_[k0 + e] = t0 + in.triangle_offset[e];
        std::copy(in.triangles.begin(), in.triangles.end(), wall_triangle_.begin() + t0);
    }
}

}  // namespace sabo::dem
