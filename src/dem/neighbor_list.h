// SPDX-License-Identifier: MIT
// Verlet neighbour list built with linked cells (docs/dem.md).
//
// Half list: for each mobile i, the partners j > i (mobile or fixed) with |x_j − x_i| < r_i + r_j + h_i +
// h_j, h the particles' half-skins (per grain: a fast grain gets a wider one, docs/dem.md), stored CSR
// (begin(i)..end(i) index `partner`). A transposed index numbers, for each particle j, the pair entries in
// which it is the partner, in ascending i (slots t_begin(j)..t_end(j); t_slot(k) is the slot of entry k).
// Both orders depend only on the positions, never on the thread count, so per-pair results can be gathered in
// a fixed order: forces are bit-identical at any thread count (docs/dem.md). Also keeps, per mobile particle,
// the walls within 2 h_i of it (wall candidates) and, for a mesh wall, its triangles within 2 h_i. The list
// stays valid while every mobile grain has moved less than its half-skin: a pair left out was farther apart
// than r_i + r_j + h_i + h_j, so it can touch only after one of them moved more than its h.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec3.h"
#include "dem/walls.h"

namespace sabo::dem {

struct Particles;

class NeighborList {
  public:
    // Builds lists for the current positions: `half_skin` holds h_i of each mobile grain; fixed spheres
    // (which never move) get `fixed_half_skin`. Cell edge = the largest 2 (r + h). Only the first `rows`
    // mobile grains get rows (partners and walls); the others (ghost copies of grains another process owns,
    // parallel/grain_halo.h) are partners of those rows only.
    void build(const Particles& p, const std::vector<Wall>& walls, std::span<const double> half_skin,
               double fixed_half_skin, std::size_t rows);

    // True when some mobile particle moved more than its half-skin since the last build.
    [[nodiscard]] bool needs_rebuild(const Particles& p) const;
    // How far grain i at x is past its half-skin: |x − x_build|² − h_i² (> 0: the list must be rebuilt).
    [[nodiscard]] double excess(std::size_t i, const Vec3& x) const {
        return norm2(x - at_build_[i].x) - at_build_[i].half_skin2;
    }
    // The same test when the caller already knows the largest excess().
    [[nodiscard]] bool needs_rebuild(double max_excess) const { return builds_ == 0 || max_excess > 0.0; }

    [[nodiscard]] std::uint32_t begin(std::size_t i) const { return offset_[i]; }
    [[nodiscard]] std::uint32_t end(std::size_t i) const { return offset_[i + 1]; }
    [[nodiscard]] std::uint32_t partner(std::uint32_t k) const { return partner_[k]; }
    [[nodiscard]] std::size_t pair_count() const { return partner_.size(); }
    [[nodiscard]] const std::vector<std::uint32_t>& partners() const { return partner_; }
    // Owner i of each entry (begin(i) <= k < end(i)): lets a run of entries be walked as one sequence.
    [[nodiscard]] const std::vector<std::uint32_t>& owners() const { return owner_; }
    [[nodiscard]] const std::vector<std::uint32_t>& offsets() const { return offset_; }
    [[nodiscard]] const std::vector<std::uint32_t>& wall_offsets() const { return wall_offset_; }
    [[nodiscard]] const std::vector<std::uint16_t>& walls() const { return wall_; }

    // Transposed slots of the entries where particle j is the partner, ascending i.
    [[nodiscard]] std::uint32_t t_begin(std::size_t j) const { return t_offset_[j]; }
    [[nodiscard]] std::uint32_t t_end(std::size_t j) const { return t_offset_[j + 1]; }
    [[nodiscard]] const std::vector<std::uint32_t>& t_slots() const { return t_slot_; }
    // Smallest i that has particle j as a partner (no_owner if none).
    static constexpr std::uint32_t no_owner = 0xffffffffU;
    [[nodiscard]] std::uint32_t first_owner(std::size_t j) const { return first_owner_[j]; }

    // Candidate walls of mobile particle i.
    [[nodiscard]] std::uint32_t wall_begin(std::size_t i) const { return wall_offset_[i]; }
    [[nodiscard]] std::uint32_t wall_end(std::size_t i) const { return wall_offset_[i + 1]; }
    [[nodiscard]] std::uint16_t wall(std::uint32_t k) const { return wall_[k]; }
    // Candidate triangles of wall entry k. A mesh wall has mesh_slots entries in a row (dem/mesh_contacts.h:
    // one per contact it can keep with the grain); the first holds the part's triangles within 2 h_i of the
    // grain, ascending, the others and the other shapes' entries none.
    [[nodiscard]] std::span<const std::uint32_t> triangles(std::uint32_t k) const {
        return {wall_triangle_.data() + wall_triangle_offset_[k],
                wall_triangle_offset_[k + 1] - wall_triangle_offset_[k]};
    }

    // Hands the rows of the current lists (pair offsets and partners, wall offsets and walls) to the caller
    // in exchange for its vectors, whose capacity the next build() reuses: what a rebuild keeps of the old
    // lists to carry the contact histories over, without copying them.
    void exchange_rows(std::vector<std::uint32_t>& offset, std::vector<std::uint32_t>& partner,
                       std::vector<std::uint32_t>& wall_offset, std::vector<std::uint16_t>& wall) {
        offset_.swap(offset);
        partner_.swap(partner);
        wall_offset_.swap(wall_offset);
        wall_.swap(wall);
    }

    [[nodiscard]] std::size_t builds() const { return builds_; }
    // Checkpoints (io/checkpoint.h): the lists and the positions they were built at; the cell grid and
    // the staging rows are scratch of the next build.
    template <class Archive>
    void transfer(Archive& a) {
        a(builds_, at_build_, offset_, partner_, owner_, t_offset_, t_slot_, first_owner_, wall_offset_,
          wall_, wall_triangle_offset_, wall_triangle_, stage_capacity_);
    }
    [[nodiscard]] std::size_t bytes() const;
    // After transfer() read a checkpoint: true when the lists fit `n` particles (`n_mobile` of them mobile)
    // and `walls` — every offset ascending and ending at its list's length, every index in range,
    // and its triangle candidates index `walls`' meshes — so that no later step reads outside them.
    [[nodiscard]] bool consistent(std::size_t n, std::size_t n_mobile, const std::vector<Wall>& walls) const;

  private:
    std::size_t builds_ = 0;
    struct AtBuild {  // one cache-friendly record per mobile grain for the displacement check
        Vec3 x;
        double half_skin2;
    };
    std::vector<AtBuild> at_build_;
    std::vector<std::uint32_t> offset_, partner_, owner_;
    std::vector<std::uint32_t> t_offset_, t_slot_, first_owner_;
    std::vector<std::uint32_t> wall_offset_;
    std::vector<std::uint16_t> wall_;
    std::vector<std::uint32_t> wall_triangle_offset_, wall_triangle_;  // per wall entry (CSR)
    // staging rows of the single-pass build
    std::uint32_t stage_capacity_ = 32;
    std::vector<std::uint32_t> stage_;
    std::vector<std::uint32_t> triangle_count_;  // per grain, of the wall candidates' build
    // the wall candidates of a chunk of grains, built apart and then copied in order
    struct WallChunk {
        std::vector<std::uint16_t> wall;
        std::vector<std::uint32_t> triangle_offset, triangles;
    };
    std::vector<WallChunk> wall_chunks_;
    [[nodiscard]] std::size_t chunk_bytes() const;
    // scratch of the parallel counting sorts: per-thread counts (threads x keys), then one total per thread
    std::vector<std::uint32_t> histogram_;
    // linked cells (kept to avoid reallocation)
    std::vector<std::uint32_t> cell_of_, cell_start_, cell_items_;
    // position and reach (radius + half-skin) of cell_items_[s] at index s: the candidate scan reads
    // them in sequence
    struct CellEntry {
        double x, y, z, reach;
    };
    std::vector<CellEntry> cell_entry_;
};

}  // namespace sabo::dem
