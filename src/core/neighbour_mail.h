// SPDX-License-Identifier: MIT
// Messages between each rank and the ranks before and after it (a row of slabs: docs/scaling.md, "How the
// ghost planes travel"). Where two neighbours run on one machine, each writes its message into memory the
// two share and the other reads it from there after one short signal: one copy for the message, where the
// MPI transport makes two or three in fragments of tens of kB (measured: a halo's messages of 0.4 MB took
// 0.3–0.5 ms that way on a 2-core machine, the step's largest wait). Between machines, ordinary messages.
// Without MPI, or on one process, there are no neighbours and an exchange does nothing.
//
// Use: write into outbox(side) (up to capacity() bytes), exchange(sizes), read inbox(side). The shared
// outboxes are double buffered: a rank writes an outbox again two exchanges later, after the next
// exchange's signal, by which the neighbour has finished reading it.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "core/mpi_world.h"

namespace sabo {

enum class Side { left = 0, right = 1 };

class NeighbourMail {
  public:
    // Collective over the world: every rank's messages hold up to `capacity` bytes (the same on every
    // rank). `share_memory` false: ordinary messages even on one machine (the tests of both ways).
    NeighbourMail(const MpiWorld& world, std::size_t capacity, bool share_memory = true);
    ~NeighbourMail();
    NeighbourMail(const NeighbourMail&) = delete;
    NeighbourMail& operator=(const NeighbourMail&) = delete;

    // The neighbouring rank on `side` (−1: none, at the row's end).
    [[nodiscard]] int neighbour(Side side) const { return neighbour_[index(side)]; }
    // Whether the neighbour on `side` reads this rank's messages from shared memory.
    [[nodiscard]] bool shared(Side side) const { return peer_[index(side)] != nullptr; }
    [[nodiscard]] std::size_t capacity() const { return capacity_; }

    // Where to write this exchange's message to the neighbour on `side` (capacity() bytes; empty: none).
    [[nodiscard]] std::span<std::byte> outbox(Side side);
    // Sends the first `bytes[side]` bytes of each outbox and receives the neighbours' messages. Collective
    // with the neighbours.
    void exchange(std::array<std::size_t, 2> bytes);
    // What the neighbour on `side` sent in the last exchange (empty: no neighbour).
    [[nodiscard]] std::span<const std::byte> inbox(Side side) const;

  private:
    static std::size_t index(Side side) { return static_cast<std::size_t>(side); }
    // this rank's outbox toward `side` in `slot`, and the neighbour's toward this rank
    [[nodiscard]] std::byte* own_box(std::size_t slot, Side side) const;
    [[nodiscard]] const std::byte* peer_box(std::size_t slot, Side side) const;

    std::size_t capacity_;
    std::size_t box_bytes_;  // a box: its size (8 bytes), then the message
    std::array<int, 2> neighbour_{-1, -1};
    std::array<std::byte*, 2> peer_{nullptr, nullptr};  // the neighbours' shared blocks
    std::byte* own_ = nullptr;                          // this rank's shared block (4 boxes)
    std::size_t write_slot_ = 0, read_slot_ = 0;        // the double buffer's halves
    std::array<std::vector<std::byte>, 2> out_, in_;    // the messages of a side that shares nothing
    std::array<std::size_t, 2> in_bytes_{0, 0};
    struct Window;
    std::unique_ptr<Window> window_;  // the shared memory's MPI handles
};

}  // namespace sabo
