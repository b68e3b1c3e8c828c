// SPDX-License-Identifier: MIT
#include "core/neighbour_mail.h"

#include <cstring>
#include <stdexcept>

#ifdef SABO_HAVE_MPI
#include <mpi.h>
#endif

namespace sabo {

namespace {

constexpr std::size_t header = 64;  // a box's message size, then its message at a cache line's start
constexpr int mail_tag = 7;         // (the world's other messages use tag 0)

std::size_t opposite(std::size_t side) {
    return 1 - side;
}

}  // namespace

#ifdef SABO_HAVE_MPI
struct NeighbourMail::Window {
    MPI_Comm node = MPI_COMM_NULL;
    MPI_Win win = MPI_WIN_NULL;
};
#else
struct NeighbourMail::Window {};
#endif

NeighbourMail::NeighbourMail(const MpiWorld& world, std::size_t capacity, bool share_memory)
    : capacity_(capacity), box_bytes_(header + (capacity + header - 1) / header * header) {
    const int rank = world.rank(), size = world.size();
    neighbour_ = {rank > 0 ? rank - 1 : -1, rank + 1 < size ? rank + 1 : -1};
#ifdef SABO_HAVE_MPI
    if (size > 1) {
        window_ = std::make_unique<Window>();
        MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &window_->node);
        // the neighbours' places among this machine's ranks (MPI_UNDEFINED: on another machine)
        MPI_Group world_group = MPI_GROUP_NULL, node_group = MPI_GROUP_NULL;
        MPI_Comm_group(MPI_COMM_WORLD, &world_group);
        MPI_Comm_group(window_->node, &node_group);
        std::array<int, 2> on_node{MPI_UNDEFINED, MPI_UNDEFINED};
        for (std::size_t s = 0; s < 2; ++s)
            if (neighbour_[s] >= 0 && share_memory)
                MPI_Group_translate_ranks(world_group, 1, &neighbour_[s], node_group, &on_node[s]);
        MPI_Group_free(&world_group);
        MPI_Group_free(&node_group);
        const bool shares = on_node[0] != MPI_UNDEFINED || on_node[1] != MPI_UNDEFINED;
        // (collective over the machine's ranks: a rank that shares with no neighbour asks for nothing)
        MPI_Info info = MPI_INFO_NULL;
        MPI_Info_create(&info);
        MPI_Info_set(info, "alloc_shared_noncontig", "true");  // each block in its own rank's memory
        void* base = nullptr;
        MPI_Win_allocate_shared(static_cast<MPI_Aint>(shares ? 4 * box_bytes_ : 0), 1, info, window_->node,
                                &base, &window_->win);
        MPI_Info_free(&info);
        own_ = static_cast<std::byte*>(base);
        MPI_Win_lock_all(MPI_MODE_NOCHECK, window_->win);
        for (std::size_t s = 0; s < 2; ++s) {
            if (on_node[s] == MPI_UNDEFINED) continue;
            MPI_Aint bytes = 0;
            int unit = 0;
            void* peer = nullptr;
            MPI_Win_shared_query(window_->win, on_node[s], &bytes, &unit, &peer);
            if (static_cast<std::size_t>(bytes) < 4 * box_bytes_)
                throw std::logic_error(
                    "NeighbourMail: the neighbour's shared block is smaller than this one's");
            peer_[s] = static_cast<std::byte*>(peer);
        }
    }
#else
    (void)share_memory;
#endif
    for (std::size_t s = 0; s < 2; ++s)
        if (neighbour_[s] >= 0 && peer_[s] == nullptr) {
            out_[s].resize(capacity_);
            in_[s].resize(capacity_);
        }
}

NeighbourMail::~NeighbourMail() {
#ifdef SABO_HAVE_MPI
    if (window_) {
        MPI_Win_unlock_all(window_->win);
        MPI_Win_free(&window_->win);
        MPI_Comm_free(&window_->node);
    }
#endif
}

std::byte* NeighbourMail::own_box(std::size_t slot, Side side) const {
    return own_ + (2 * slot + index(side)) * box_bytes_;
}

const std::byte* NeighbourMail::peer_box(std::size_t slot, Side side) const {
    // what the neighbour on `side` wrote toward this rank: its box toward the other side
    return peer_[index(side)] + (2 * slot + opposite(index(side))) * box_bytes_;
}

std::span<std::byte> NeighbourMail::outbox(Side side) {
    const std::size_t s = index(side);
    if (neighbour_[s] < 0) return {};
    if (peer_[s] != nullptr) return {own_box(write_slot_, side) + header, capacity_};
    return out_[s];
}

std::span<const std::byte> NeighbourMail::inbox(Side side) const {
    const std::size_t s = index(side);
    if (neighbour_[s] < 0) return {};
    if (peer_[s] != nullptr) return {peer_box(read_slot_, side) + header, in_bytes_[s]};
    return std::span(in_[s]).first(in_bytes_[s]);
}

void NeighbourMail::exchange(std::array<std::size_t, 2> bytes) {
    for (std::size_t s = 0; s < 2; ++s)
        if (neighbour_[s] >= 0 && bytes[s] > capacity_)
            throw std::logic_error("NeighbourMail: a message larger than the capacity it was built for");
#ifdef SABO_HAVE_MPI
    if (!window_) return;
    const bool shares = peer_[0] != nullptr || peer_[1] != nullptr;
    for (std::size_t s = 0; s < 2; ++s)
        if (peer_[s] != nullptr)
            std::memcpy(own_box(write_slot_, static_cast<Side>(s)), &bytes[s], sizeof(bytes[s]));
    if (shares) MPI_Win_sync(window_->win);  // the outboxes written before the neighbours hear so
    std::array<MPI_Request, 4> requests{MPI_REQUEST_NULL, MPI_REQUEST_NULL, MPI_REQUEST_NULL,
                                        MPI_REQUEST_NULL};
    std::array<MPI_Status, 4> status{};
    char token_out = 1;
    std::array<char, 2> token_in{};
    for (std::size_t s = 0; s < 2; ++s) {
        const int n = neighbour_[s];
        if (n < 0) continue;
        if (peer_[s] != nullptr) {  // a signal: the message waits in shared memory
            MPI_Irecv(&token_in[s], 1, MPI_CHAR, n, mail_tag, MPI_COMM_WORLD, &requests[2 * s]);
            MPI_Isend(&token_out, 1, MPI_CHAR, n, mail_tag, MPI_COMM_WORLD, &requests[2 * s + 1]);
        } else {
            MPI_Irecv(in_[s].data(), static_cast<int>(capacity_), MPI_BYTE, n, mail_tag, MPI_COMM_WORLD,
                      &requests[2 * s]);
            MPI_Isend(out_[s].data(), static_cast<int>(bytes[s]), MPI_BYTE, n, mail_tag, MPI_COMM_WORLD,
                      &requests[2 * s + 1]);
        }
    }
    MPI_Waitall(4, requests.data(), status.data());
    if (shares) MPI_Win_sync(window_->win);  // the neighbours' outboxes as they wrote them
    read_slot_ = write_slot_;
    write_slot_ = 1 - write_slot_;
    for (std::size_t s = 0; s < 2; ++s) {
        if (neighbour_[s] < 0) continue;
        if (peer_[s] != nullptr) {
            std::memcpy(&in_bytes_[s], peer_box(read_slot_, static_cast<Side>(s)), sizeof(in_bytes_[s]));
        } else {
            int count = 0;
            MPI_Get_count(&status[2 * s], MPI_BYTE, &count);
            in_bytes_[s] = static_cast<std::size_t>(count);
        }
    }
#endif
}

}  // namespace sabo
