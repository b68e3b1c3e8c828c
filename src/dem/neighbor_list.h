// SPDX-License-Identifier: MIT
// Verlet neighbour list built with linked cells (SPEC §1.6).
//
// Half list: for each mobile i, the partners j > i (mobile or fixed) with |x_j − x_i| < r_i + r_j + skin,
// stored CSR (begin(i)..end(i) index `partner`). A transposed index numbers, for each particle j,
// the pair entries in which it is the partner, in ascending i (slots t_begin(j)..t_end(j);
// t_slot(k) is the slot of entry k). Both orders depend only on the
// positions, never on the thread count, so per-pair results can be gathered in a fixed order:
// forces are bit-identical at any thread count (docs/dem.md).
// Also keeps, per mobile particle, the walls within `skin` of it (wall candidates).
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "dem/walls.h"

namespace sabo::dem {

struct Particles;

class NeighborList {
  public:
    // Builds lists for the current positions. Cell edge = largest diameter + skin.
    void build(const Particles& p, const std::vector<Wall>& walls, double skin);

    // True when some mobile particle moved more than skin/2 since the last build.
    [[nodiscard]] bool needs_rebuild(const Particles& p) const;
    // The same test when the caller already knows the largest squared displacement.
    [[nodiscard]] bool needs_rebuild(double max_displacement2) const {
        return builds_ == 0 || max_displacement2 > 0.25 * skin_ * skin_;
    }
    // Position of mobile particle i at the last build.
    [[nodiscard]] const Vec3& reference_position(std::size_t i) const { return x_at_build_[i]; }

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
    [[nodiscard]] std::size_t bytes() const;

  private:
    double skin_ = 0.0;
    std::size_t builds_ = 0;
    std::vector<Vec3> x_at_build_;
    std::vector<std::uint32_t> offset_, partner_, owner_;
    std::vector<std::uint32_t> t_offset_, t_slot_, first_owner_;
    std::vector<std::uint32_t> wall_offset_;
    std::vector<std::uint16_t> wall_;
    // staging rows of the single-pass build
    std::uint32_t stage_capacity_ = 32;
    std::vector<std::uint32_t> stage_;
    std::vector<std::uint16_t> wall_stage_;
    // scratch of the parallel counting sorts: per-thread counts (threads x keys), then one total per thread
    std::vector<std::uint32_t> histogram_;
    // linked cells (kept to avoid reallocation)
    std::vector<std::uint32_t> cell_of_, cell_start_, cell_items_;
    // position and radius of cell_items_[s] at index s: the candidate scan reads them in sequence
    struct CellEntry {
        double x, y, z, r;
    };
    std::vector<CellEntry> cell_entry_;
};

}  // namespace sabo::dem
