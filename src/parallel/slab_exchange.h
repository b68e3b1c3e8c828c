// SPDX-License-Identifier: MIT
// The ghost planes of one rank's slab (docs/scaling.md): a rank stores its `planes` planes after `ghosts`
// ghost planes that mirror the left neighbour's last planes and before `ghosts` that mirror the right
// neighbour's first ones (none toward the domain's ends), in the lattice's layout (x fastest, rows of `row`
// cells, index = x + row·y + plane·z). `fill_ghosts` copies the neighbours' edge planes into the ghosts
// (what a step reads across the face); `return_ghosts` sends the ghosts back onto the neighbours' edge
// planes (what a step wrote across the face: the AA pattern's odd step streams populations into the
// neighbour's slots). One field at a time: a population, a fill fraction, a cell type.
#pragma once
#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/mpi_world.h"

namespace sabo::parallel {

struct SlabLayout {
    int planes = 0;  // the slab's own planes
    int ghosts = 1;  // ghost planes toward each neighbour
    int ny = 0, nz = 0;
    std::size_t row = 0;    // cells from one row to the next (≥ the local planes)
    std::size_t plane = 0;  // cells from one z-layer to the next (≥ row · ny)
    [[nodiscard]] std::size_t index(int x, int y, int z) const {
        return static_cast<std::size_t>(x) + row * static_cast<std::size_t>(y) +
               plane * static_cast<std::size_t>(z);
    }
};

class SlabExchange {
  public:
    // This process's slab, rank `world.rank()` of `world.size()` in a row of slabs: its neighbours are the
    // ranks before and after it.
    // `fields`: the most fields one message carries (its buffers are sized for them once, here).
    SlabExchange(const MpiWorld& world, const SlabLayout& layout, int fields = 1);

    // Local x of the slab's first own plane (after the left ghosts) and the number of local planes.
    [[nodiscard]] int first_own() const { return left_ >= 0 ? layout_.ghosts : 0; }
    // The neighbouring ranks (−1: none, at the domain's end).
    [[nodiscard]] int left() const { return left_; }
    [[nodiscard]] int right() const { return right_; }
    [[nodiscard]] int local_planes() const {
        return layout_.planes + (left_ >= 0 ? layout_.ghosts : 0) + (right_ >= 0 ? layout_.ghosts : 0);
    }

    template <class T>
    void fill_ghosts(std::span<T> field) {
        fill_ghosts(std::span<const std::span<T>>(&field, 1));
    }
    // Several fields of one type in one message per face (a step's populations: one latency, not 19).
    template <class T>
    void fill_ghosts(std::span<const std::span<T>> fields) {
        const int g = layout_.ghosts, own = first_own(), end = own + layout_.planes;
        // the first own planes to the left, the right neighbour's into the right ghosts; then the mirror
        shift<T>(fields, own, left_, end, right_);
        shift<T>(fields, end - g, right_, 0, left_);
    }

    template <class T>
    void return_ghosts(std::span<T> field) {
        const int g = layout_.ghosts, own = first_own(), end = own + layout_.planes;
        const std::span<const std::span<T>> fields(&field, 1);
        shift<T>(fields, 0, left_, end - g, right_);
        shift<T>(fields, end, right_, own, left_);
    }

  private:
    // Sends the `ghosts` planes from local x `from_x` on of every field to rank `to` while those from
    // `into_x` on receive from rank `from` (−1: no rank).
    template <class T>
    void shift(std::span<const std::span<T>> fields, int from_x, int to, int into_x, int from) {
        static_assert(sizeof(T) <= sizeof(double), "the plane buffers hold values of up to 8 bytes");
        const std::size_t bytes = sizeof(T) * cells_ * fields.size();
        if (send_.size() < bytes)
            throw std::logic_error("SlabExchange: more fields in one message than it was built for");
        if (to >= 0) rows<T, true>(fields, from_x, send_.data());
        world_.send_receive(std::span(send_).first(to >= 0 ? bytes : 0), to,
                            std::span(receive_).first(from >= 0 ? bytes : 0), from);
        if (from >= 0) rows<T, false>(fields, into_x, receive_.data());
    }

    // Copies the `ghosts` planes from local x `x0` on of every field into the buffer (Pack) or back. The
    // ghost planes of a row are neighbours in memory: one copy per row and field, of a size known to the
    // compiler for the usual depths (a call to memmove for each of these short runs cost more than the
    // exchange's MPI transfer).
    template <class T, bool Pack>
    void rows(std::span<const std::span<T>> fields, int x0, std::byte* buffer) const {
        switch (layout_.ghosts) {
            case 1:
                return rows<T, Pack, 1>(fields, x0, buffer);
            case 2:
                return rows<T, Pack, 2>(fields, x0, buffer);
            case 3:
                return rows<T, Pack, 3>(fields, x0, buffer);
            case 4:
                return rows<T, Pack, 4>(fields, x0, buffer);
            case 7:
                return rows<T, Pack, 7>(fields, x0, buffer);
            default:
                return rows<T, Pack, 0>(fields, x0, buffer);
        }
    }
    template <class T, bool Pack, int Ghosts>
    void rows(std::span<const std::span<T>> fields, int x0, std::byte* buffer) const {
        const std::size_t run = sizeof(T) * static_cast<std::size_t>(Ghosts > 0 ? Ghosts : layout_.ghosts);
        for (const std::span<T>& field : fields)
            for (int z = 0; z < layout_.nz; ++z)
                for (int y = 0; y < layout_.ny; ++y, buffer += run) {
                    T* cells = &field[layout_.index(x0, y, z)];
                    if constexpr (Pack)
                        std::memcpy(buffer, cells, Ghosts > 0 ? sizeof(T) * Ghosts : run);
                    else
                        std::memcpy(cells, buffer, Ghosts > 0 ? sizeof(T) * Ghosts : run);
                }
    }

    const MpiWorld& world_;
    SlabLayout layout_;
    int left_, right_;
    std::size_t cells_;                      // ghosts · ny · nz: the planes of one exchange
    std::vector<std::byte> send_, receive_;  // those planes of the fields of one message
};

}  // namespace sabo::parallel
