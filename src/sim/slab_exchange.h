// SPDX-License-Identifier: MIT
// The ghost planes of one rank's slab (docs/scaling.md): a rank stores its planes with one ghost plane on
// each side, local x = 0 (the left neighbour's last plane) and x = n + 1 (the right neighbour's first), in
// the lattice's layout (x fastest, rows of `row` cells, index = x + row·y + plane·z). `fill_ghosts` copies
// the neighbours' edge planes into the ghosts (what a step reads across the face); `return_ghosts` sends
// the ghosts back onto the neighbours' edge planes (what a step wrote across the face: the AA pattern's
// odd step streams populations into the neighbour's slots). One field at a time: a population, a fill
// fraction, a cell type.
#pragma once
#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include "core/mpi_world.h"

namespace sabo::sim {

struct SlabLayout {
    int planes = 0;  // the slab's own planes, n (the ghosts at local x = 0 and n + 1)
    int ny = 0, nz = 0;
    std::size_t row = 0;    // cells from one row to the next (≥ n + 2)
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
    SlabExchange(const MpiWorld& world, const SlabLayout& layout);

    template <class T>
    void fill_ghosts(std::span<T> field) {
        // first own plane to the left, the right neighbour's into the right ghost; then the mirror image
        shift<T>(field, 1, left_, layout_.planes + 1, right_);
        shift<T>(field, layout_.planes, right_, 0, left_);
    }

    template <class T>
    void return_ghosts(std::span<T> field) {
        shift<T>(field, 0, left_, layout_.planes, right_);
        shift<T>(field, layout_.planes + 1, right_, 1, left_);
    }

  private:
    // Sends plane `from_x` to rank `to` while plane `into_x` receives from rank `from` (−1: no rank).
    template <class T>
    void shift(std::span<T> field, int from_x, int to, int into_x, int from) {
        static_assert(sizeof(T) <= sizeof(double), "the plane buffers hold values of up to 8 bytes");
        const std::size_t bytes = sizeof(T) * cells_;
        if (to >= 0) {
            std::size_t n = 0;
            for (int z = 0; z < layout_.nz; ++z)
                for (int y = 0; y < layout_.ny; ++y, n += sizeof(T))
                    std::memcpy(send_.data() + n, &field[layout_.index(from_x, y, z)], sizeof(T));
        }
        world_.send_receive(std::span(send_).first(to >= 0 ? bytes : 0), to,
                            std::span(receive_).first(from >= 0 ? bytes : 0), from);
        if (from >= 0) {
            std::size_t n = 0;
            for (int z = 0; z < layout_.nz; ++z)
                for (int y = 0; y < layout_.ny; ++y, n += sizeof(T))
                    std::memcpy(&field[layout_.index(into_x, y, z)], receive_.data() + n, sizeof(T));
        }
    }

    const MpiWorld& world_;
    SlabLayout layout_;
    int left_, right_;
    std::size_t cells_;                      // ny · nz: one plane
    std::vector<std::byte> send_, receive_;  // one plane of the widest field (8-byte values)
};

}  // namespace sabo::sim
