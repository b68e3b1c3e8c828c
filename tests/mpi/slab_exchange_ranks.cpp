// SPDX-License-Identifier: MIT
// The ghost-plane exchange between slabs, run on 1, 2 and 3 processes (`mpiexec -n N`; ctest
// slab_exchange_*): each rank's slab of a 12-plane channel holds, in every cell, a value naming its global
// plane, y and z, with 1 and with 2 ghost planes toward each neighbour. After fill_ghosts every local plane
// holds its global plane's value; after return_ghosts each edge plane holds what the neighbour wrote into
// its ghosts and the inner planes are untouched; a message of three blocks (two fields of different types
// and a list of records of a length only the sender knows) arrives whole from both neighbours. Each both
// through shared memory and by ordinary messages. Prints "slab exchange passed" on rank 0, or exits with 1
// naming the first wrong cell.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/mpi_world.h"
#include "parallel/slab_exchange.h"
#include "parallel/slab_partition.h"

namespace {

template <class T>
T value(int global_x, int y, int z) {
    return static_cast<T>(1000 * global_x + 10 * y + z);
}

template <class T>
int check_field(const sabo::MpiWorld& world, const sabo::parallel::SlabPartition& slabs, int ghosts,
                bool share_memory) {
    const int rank = world.rank(), n = slabs.end(rank) - slabs.begin(rank), x0 = slabs.begin(rank);
    const bool has_left = rank > 0, has_right = rank + 1 < world.size();
    sabo::parallel::SlabLayout layout{n, ghosts, 5, 3, static_cast<std::size_t>(n + 2 * ghosts + 3),
                                      0};  // padded
    layout.plane = layout.row * layout.ny + 7;
    const T untouched = static_cast<T>(-1);
    std::vector<T> field(layout.plane * layout.nz, untouched);
    sabo::parallel::SlabExchange exchange(world, layout, sizeof(double), share_memory);
    const int own = exchange.first_own(), end = own + n;
    // local plane x holds global plane x0 + x − own
    const auto global = [&](int x) { return x0 + x - own; };
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y)
            for (int x = own; x < end; ++x) field[layout.index(x, y, z)] = value<T>(global(x), y, z);
    auto expect = [&](int x, int y, int z, T want, const char* what) {
        if (field[layout.index(x, y, z)] == want) return true;
        std::fprintf(stderr, "rank %d, %d ghost(s): %s: local plane %d (%d, %d) holds %g, expected %g\n",
                     rank, ghosts, what, x, y, z, static_cast<double>(field[layout.index(x, y, z)]),
                     static_cast<double>(want));
        return false;
    };
    if (exchange.local_planes() != n + (has_left ? ghosts : 0) + (has_right ? ghosts : 0)) return 1;
    exchange.fill_ghosts(std::span(field));
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y)
            for (int x = 0; x < exchange.local_planes(); ++x)
                if (!expect(x, y, z, value<T>(global(x), y, z), "fill")) return 1;
    // what a step "wrote" into the ghosts: minus their global plane's value
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y)
            for (int x = 0; x < exchange.local_planes(); ++x)
                if (x < own || x >= end) field[layout.index(x, y, z)] = -value<T>(global(x), y, z);
    exchange.return_ghosts(std::span(field));
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y)
            for (int x = own; x < end; ++x) {
                const bool returned = (has_left && x < own + ghosts) || (has_right && x >= end - ghosts);
                const T want = returned ? -value<T>(global(x), y, z) : value<T>(global(x), y, z);
                if (!expect(x, y, z, want, returned ? "return, edge plane" : "return, inner plane")) return 1;
            }
    return 0;
}

// A message of a float field, an int8 field, records and a double field in marked rows only: rank r sends
// toward each side r + 1 + repeat records valued 100 r + the record's place (+ 0.5 toward the right), and of
// the double field the rows (y, z) it marks for that side (marked()); the ghosts' other rows keep their
// values.
int check_message(const sabo::MpiWorld& world, const sabo::parallel::SlabPartition& slabs, int ghosts,
                  bool share_memory, int repeat) {
    using sabo::Side;
    const int rank = world.rank(), n = slabs.end(rank) - slabs.begin(rank), x0 = slabs.begin(rank);
    sabo::parallel::SlabLayout layout{n, ghosts, 4, 2, static_cast<std::size_t>(n + 2 * ghosts), 0};
    layout.plane = layout.row * layout.ny;
    // a float, an int8, up to 8 records of one double, a double and a row's mark per ghost cell
    sabo::parallel::SlabExchange exchange(world, layout, sizeof(float) + 1 + 9 * sizeof(double) + 1,
                                          share_memory);
    std::vector<float> a(layout.plane * layout.nz, -1.0F);
    std::vector<std::int8_t> b(a.size(), -1);
    std::vector<double> c(a.size(), -1.0);
    const auto marked = [&](int from, Side side, int y, int z) {
        return (y + 2 * z + from + static_cast<int>(side) + repeat) % 3 != 0;
    };
    const int own = exchange.first_own();
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y)
            for (int x = own; x < own + n; ++x) {
                a[layout.index(x, y, z)] = value<float>(x0 + x - own, y, z);
                b[layout.index(x, y, z)] = static_cast<std::int8_t>((x0 + x - own + repeat) % 100);
                c[layout.index(x, y, z)] = value<double>(x0 + x - own, y, z);
            }
    const auto records = [&](int from, Side side) {
        std::vector<double> r(static_cast<std::size_t>(from + 1 + repeat));
        for (std::size_t i = 0; i < r.size(); ++i)
            r[i] = 100.0 * from + static_cast<double>(i) + (side == Side::right ? 0.5 : 0.0);
        return r;
    };
    // (each side's blocks in one order: the neighbour unpacks them in it)
    exchange.pack_edges(std::span(a));
    exchange.pack_records(Side::left, records(rank, Side::left));
    exchange.pack_records(Side::right, records(rank, Side::right));
    for (const Side side : {Side::left, Side::right}) {
        std::vector<std::uint8_t> marks;
        for (int z = 0; z < layout.nz; ++z)
            for (int y = 0; y < layout.ny; ++y) marks.push_back(marked(rank, side, y, z) ? 1 : 0);
        exchange.pack_rows(side, marks);
    }
    const std::span<double> c_field(c);
    exchange.pack_marked_edges(std::span<const std::span<double>>(&c_field, 1));
    exchange.pack_edges(std::span(b));
    exchange.send();
    exchange.unpack_ghosts(std::span(a));
    const std::span<const double> from_left = exchange.unpack_records(Side::left);
    const std::span<const double> from_right = exchange.unpack_records(Side::right);
    exchange.unpack_rows();
    exchange.unpack_marked_ghosts(std::span<const std::span<double>>(&c_field, 1));
    exchange.unpack_ghosts(std::span(b));
    int wrong = 0;
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y)
            for (int x = 0; x < exchange.local_planes(); ++x) {
                const int global = x0 + x - own;
                wrong += a[layout.index(x, y, z)] != value<float>(global, y, z) ? 1 : 0;
                wrong +=
                    b[layout.index(x, y, z)] != static_cast<std::int8_t>((global + repeat) % 100) ? 1 : 0;
                // a ghost's row travelled if its sender (the left neighbour toward its right side, the right
                // one toward its left) marked it
                const bool ghost = x < own || x >= own + n;
                const bool travelled = !ghost || (x < own ? marked(rank - 1, Side::right, y, z)
                                                          : marked(rank + 1, Side::left, y, z));
                wrong += c[layout.index(x, y, z)] != (travelled ? value<double>(global, y, z) : -1.0) ? 1 : 0;
            }
    // the left neighbour's records toward its right, the right one's toward its left
    const auto expect = [&](std::span<const double> got, int from, Side side) {
        if (from < 0 || from >= world.size()) return got.empty() ? 0 : 1;
        const std::vector<double> want = records(from, side);
        return std::equal(got.begin(), got.end(), want.begin(), want.end()) ? 0 : 1;
    };
    wrong += expect(from_left, rank - 1, Side::right) + expect(from_right, rank + 1, Side::left);
    if (wrong != 0)
        std::fprintf(stderr, "rank %d, %d ghost(s), shared %d, message %d: %d wrong values\n", rank, ghosts,
                     share_memory ? 1 : 0, repeat, wrong);
    return wrong != 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    const sabo::MpiWorld world(argc, argv);
    const sabo::parallel::SlabPartition slabs(12, world.size(), 2);
    int failed = 0;
    for (const bool shared : {true, false})
        for (const int ghosts : {1, 2}) {
            failed += check_field<double>(world, slabs, ghosts, shared) +
                      check_field<float>(world, slabs, ghosts, shared) +
                      check_field<std::int32_t>(world, slabs, ghosts, shared);
            // several messages in a row: the shared memory's double buffer is reused
            for (int repeat = 0; repeat < 3; ++repeat)
                failed += check_message(world, slabs, ghosts, shared, repeat);
        }
    const auto total = world.sum(failed);
    if (world.rank() == 0 && total == 0) std::printf("slab exchange passed on %d rank(s)\n", world.size());
    return total == 0 ? 0 : 1;
}
