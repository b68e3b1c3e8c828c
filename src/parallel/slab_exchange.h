// SPDX-License-Identifier: MIT
// The ghost planes of one rank's slab (docs/scaling.md): a rank stores its `planes` planes after `ghosts`
// ghost planes that mirror the left neighbour's last planes and before `ghosts` that mirror the right
// neighbour's first ones (none toward the domain's ends), in the lattice's layout (x fastest, rows of `row`
// cells, index = x + row·y + plane·z). `fill_ghosts` copies the neighbours' edge planes into the ghosts
// (what a step reads across the face); `return_ghosts` sends the ghosts back onto the neighbours' edge
// planes (what a step wrote across the face: the AA pattern's odd step streams populations into the
// neighbour's slots). Fields of several types (populations, fill fractions, cell types) and lists of records
// travel in one message per face (pack_…, send, unpack_…), through shared memory where the neighbours run
// on one machine (core/neighbour_mail.h). A field may travel only in the rows (the `ghosts` cells of one y
// and z) the sender marks: the marks go first, in the same message, so that both sides copy the same rows.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "core/mpi_world.h"
#include "core/neighbour_mail.h"

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
    // ranks before and after it. `cell_bytes`: the most bytes one message carries per cell of the ghost
    // planes (its buffers are sized for them once, here; each block of a message is padded to 8 bytes, up
    // to 32 blocks). `share_memory`: see NeighbourMail.
    SlabExchange(const MpiWorld& world, const SlabLayout& layout, std::size_t cell_bytes = sizeof(double),
                 bool share_memory = true);

    // Local x of the slab's first own plane (after the left ghosts) and the number of local planes.
    [[nodiscard]] int first_own() const { return left() >= 0 ? layout_.ghosts : 0; }
    // The neighbouring ranks (−1: none, at the domain's end).
    [[nodiscard]] int neighbour(Side side) const { return mail_.neighbour(side); }
    [[nodiscard]] int left() const { return mail_.neighbour(Side::left); }
    [[nodiscard]] int right() const { return mail_.neighbour(Side::right); }
    [[nodiscard]] int local_planes() const {
        return layout_.planes + (left() >= 0 ? layout_.ghosts : 0) + (right() >= 0 ? layout_.ghosts : 0);
    }

    template <class T>
    void fill_ghosts(std::span<T> field) {
        fill_ghosts(std::span<const std::span<T>>(&field, 1));
    }
    // Several fields in one message per face (a step's populations: one latency, not 19).
    template <class T>
    void fill_ghosts(std::span<const std::span<T>> fields) {
        pack_edges(fields);
        send();
        unpack_ghosts(fields);
    }
    template <class T>
    void return_ghosts(std::span<T> field) {
        const std::span<const std::span<T>> fields(&field, 1);
        const int g = layout_.ghosts, own = first_own(), end = own + layout_.planes;
        transfer<T, true>(fields, 0, end);
        send();
        transfer<T, false>(fields, own, end - g);
    }

    // A message of several blocks, toward both neighbours at once: the blocks packed in order, sent, then
    // unpacked in the same order. The first and last `ghosts` own planes of every field (toward the left and
    // the right neighbour) …
    template <class T>
    void pack_edges(std::span<const std::span<T>> fields) {
        const int g = layout_.ghosts, own = first_own();
        transfer<T, true>(fields, own, own + layout_.planes - g);
    }
    template <class T>
    void pack_edges(std::span<T> field) {
        pack_edges(std::span<const std::span<T>>(&field, 1));
    }
    // … or the marks of the rows (one byte per row, y + ny·z; non-zero: the row travels) toward `side`'s
    // neighbour, then only the marked rows of fields, toward each neighbour its side's …
    void pack_rows(Side side, std::span<const std::uint8_t> marks);
    template <class T>
    void pack_marked_edges(std::span<const std::span<T>> fields) {
        const int g = layout_.ghosts, own = first_own();
        transfer<T, true>(fields, own, own + layout_.planes - g, true);
    }
    // … or a list of records toward `side`'s neighbour (its length goes first) …
    void pack_records(Side side, std::span<const double> records);
    // … then one exchange with both neighbours …
    void send();
    // … then the neighbours' edge planes into the ghost planes, in the order they were packed
    template <class T>
    void unpack_ghosts(std::span<const std::span<T>> fields) {
        transfer<T, false>(fields, 0, first_own() + layout_.planes);
    }
    template <class T>
    void unpack_ghosts(std::span<T> field) {
        unpack_ghosts(std::span<const std::span<T>>(&field, 1));
    }
    // the neighbours' marks of rows, then their marked rows
    void unpack_rows();
    template <class T>
    void unpack_marked_ghosts(std::span<const std::span<T>> fields) {
        transfer<T, false>(fields, 0, first_own() + layout_.planes, true);
    }
    // the records the neighbour on `side` packed (empty: no neighbour)
    [[nodiscard]] std::span<const double> unpack_records(Side side);

  private:
    // Packs (Pack) the `ghosts` planes from local x `left_x` on of every field toward the left neighbour and
    // those from `right_x` on toward the right one, or unpacks the neighbours' blocks into them.
    // `marked`: only the rows the side's marks name (pack_rows, unpack_rows).
    template <class T, bool Pack>
    void transfer(std::span<const std::span<T>> fields, int left_x, int right_x, bool marked = false) {
        static_assert(sizeof(T) <= sizeof(double), "blocks of values of up to 8 bytes");
        for (const Side side : {Side::left, Side::right}) {
            const std::size_t s = static_cast<std::size_t>(side);
            if (mail_.neighbour(side) < 0) continue;
            const std::uint8_t* marks = marked ? (Pack ? out_marks_[s] : in_marks_[s]) : nullptr;
            if (marked && marks == nullptr)
                throw std::logic_error("SlabExchange: marked rows without the rows' marks");
            const std::size_t count = marked ? (Pack ? out_marked_[s] : in_marked_[s]) : rows_count();
            const std::size_t bytes =
                sizeof(T) * count * static_cast<std::size_t>(layout_.ghosts) * fields.size();
            std::size_t& at = Pack ? out_at_[s] : in_at_[s];
            if (at + bytes > (Pack ? mail_.capacity() : mail_.inbox(side).size()))
                throw std::logic_error("SlabExchange: a block beyond the message's end");
            const int x = side == Side::left ? left_x : right_x;
            if constexpr (Pack)
                rows<T, true>(fields, x, mail_.outbox(side).data() + at, marks);
            else
                rows<T, false>(fields, x, mail_.inbox(side).data() + at, marks);
            at = padded(at + bytes);
        }
    }
    [[nodiscard]] std::size_t rows_count() const {
        return static_cast<std::size_t>(layout_.ny) * static_cast<std::size_t>(layout_.nz);
    }
    static std::size_t padded(std::size_t bytes) { return (bytes + 7) / 8 * 8; }

    // Copies the `ghosts` planes from local x `x0` on of every field into the buffer (Pack) or back. The
    // ghost planes of a row are neighbours in memory: one copy per row and field, of a size known to the
    // compiler for the usual depths (a call to memmove for each of these short runs cost more than the
    // exchange's MPI transfer).
    template <bool Pack>
    using Buffer = std::conditional_t<Pack, std::byte*, const std::byte*>;
    template <class T, bool Pack>
    void rows(std::span<const std::span<T>> fields, int x0, Buffer<Pack> buffer,
              const std::uint8_t* marks) const {
        switch (layout_.ghosts) {
            case 1:
                return rows<T, Pack, 1>(fields, x0, buffer, marks);
            case 2:
                return rows<T, Pack, 2>(fields, x0, buffer, marks);
            case 3:
                return rows<T, Pack, 3>(fields, x0, buffer, marks);
            case 4:
                return rows<T, Pack, 4>(fields, x0, buffer, marks);
            case 7:
                return rows<T, Pack, 7>(fields, x0, buffer, marks);
            default:
                return rows<T, Pack, 0>(fields, x0, buffer, marks);
        }
    }
    // (marks: nullptr, every row)
    template <class T, bool Pack, int Ghosts>
    void rows(std::span<const std::span<T>> fields, int x0, Buffer<Pack> buffer,
              const std::uint8_t* marks) const {
        const std::size_t run = sizeof(T) * static_cast<std::size_t>(Ghosts > 0 ? Ghosts : layout_.ghosts);
        for (const std::span<T>& field : fields)
            for (int z = 0, r = 0; z < layout_.nz; ++z)
                for (int y = 0; y < layout_.ny; ++y, ++r) {
                    if (marks != nullptr && marks[r] == 0) continue;
                    T* cells = &field[layout_.index(x0, y, z)];
                    if constexpr (Pack)
                        std::memcpy(buffer, cells, Ghosts > 0 ? sizeof(T) * Ghosts : run);
                    else
                        std::memcpy(cells, buffer, Ghosts > 0 ? sizeof(T) * Ghosts : run);
                    buffer += run;
                }
    }

    SlabLayout layout_;
    std::size_t cells_;  // ghosts · ny · nz: the planes of one block
    NeighbourMail mail_;
    // the next block's place in each side's message, to send and received
    std::array<std::size_t, 2> out_at_{0, 0}, in_at_{0, 0};
    // each side's marks of rows in the message being packed and the one received (nullptr: none yet) and
    // how many rows they mark
    std::array<const std::uint8_t*, 2> out_marks_{nullptr, nullptr}, in_marks_{nullptr, nullptr};
    std::array<std::size_t, 2> out_marked_{0, 0}, in_marked_{0, 0};
};

}  // namespace sabo::parallel
