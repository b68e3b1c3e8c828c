// SPDX-License-Identifier: MIT
#include "parallel/slab_exchange.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace sabo::parallel {

namespace {

std::size_t marked_rows(const std::uint8_t* marks, std::size_t rows) {
    return static_cast<std::size_t>(
        std::count_if(marks, marks + rows, [](std::uint8_t m) { return m != 0; }));
}

std::size_t ghost_cells(const SlabLayout& layout) {
    return static_cast<std::size_t>(layout.ghosts) * static_cast<std::size_t>(layout.ny) *
           static_cast<std::size_t>(layout.nz);
}

}  // namespace

SlabExchange::SlabExchange(const MpiWorld& world, const SlabLayout& layout, std::size_t cell_bytes,
                           bool share_memory)
    : layout_(layout),
      cells_(ghost_cells(layout)),
      mail_(world, ghost_cells(layout) * cell_bytes + 32 * 8, share_memory) {}

void SlabExchange::pack_records(Side side, std::span<const double> records) {
    const auto s = static_cast<std::size_t>(side);
    if (mail_.neighbour(side) < 0) return;
    const std::uint64_t count = records.size();
    const std::size_t bytes = sizeof(count) + records.size_bytes();
    if (out_at_[s] + bytes > mail_.capacity())
        throw std::logic_error("SlabExchange: records beyond the message's end");
    std::byte* at = mail_.outbox(side).data() + out_at_[s];
    std::memcpy(at, &count, sizeof(count));
    if (!records.empty()) std::memcpy(at + sizeof(count), records.data(), records.size_bytes());
    out_at_[s] = padded(out_at_[s] + bytes);
}

void SlabExchange::pack_rows(Side side, std::span<const std::uint8_t> marks) {
    const auto s = static_cast<std::size_t>(side);
    if (mail_.neighbour(side) < 0) return;
    if (marks.size() != rows_count())
        throw std::logic_error("SlabExchange: marks for another number of rows");
    if (out_at_[s] + marks.size() > mail_.capacity())
        throw std::logic_error("SlabExchange: marks beyond the message's end");
    std::byte* at = mail_.outbox(side).data() + out_at_[s];
    std::memcpy(at, marks.data(), marks.size());
    out_marks_[s] = reinterpret_cast<const std::uint8_t*>(at);
    out_marked_[s] = marked_rows(marks.data(), marks.size());
    out_at_[s] = padded(out_at_[s] + marks.size());
}

void SlabExchange::unpack_rows() {
    for (const Side side : {Side::left, Side::right}) {
        const auto s = static_cast<std::size_t>(side);
        if (mail_.neighbour(side) < 0) continue;
        const std::span<const std::byte> in = mail_.inbox(side);
        if (in_at_[s] + rows_count() > in.size())
            throw std::logic_error("SlabExchange: marks beyond the message's end");
        const auto* marks = reinterpret_cast<const std::uint8_t*>(in.data() + in_at_[s]);
        in_marks_[s] = marks;
        in_marked_[s] = marked_rows(marks, rows_count());
        in_at_[s] = padded(in_at_[s] + rows_count());
    }
}

void SlabExchange::send() {
    mail_.exchange(out_at_);
    out_at_ = {0, 0};
    in_at_ = {0, 0};
    out_marks_ = {nullptr, nullptr};
    in_marks_ = {nullptr, nullptr};
}

std::span<const double> SlabExchange::unpack_records(Side side) {
    const auto s = static_cast<std::size_t>(side);
    if (mail_.neighbour(side) < 0) return {};
    const std::span<const std::byte> in = mail_.inbox(side);
    std::uint64_t count = 0;
    if (in_at_[s] + sizeof(count) > in.size())
        throw std::logic_error("SlabExchange: records beyond the message's end");
    std::memcpy(&count, in.data() + in_at_[s], sizeof(count));
    const std::size_t bytes = sizeof(count) + count * sizeof(double);
    if (in_at_[s] + bytes > in.size())
        throw std::logic_error("SlabExchange: records beyond the message's end");
    const auto* records = reinterpret_cast<const double*>(in.data() + in_at_[s] + sizeof(count));
    in_at_[s] = padded(in_at_[s] + bytes);
    return {records, count};
}

}  // namespace sabo::parallel
