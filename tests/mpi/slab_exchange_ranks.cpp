// SPDX-License-Identifier: MIT
// The ghost-plane exchange between slabs, run on 1, 2 and 3 processes (`mpiexec -n N`; ctest
// slab_exchange_*): each rank's slab of a 12-plane channel holds, in every cell, a value naming its global
// plane, y and z, with 1 and with 2 ghost planes toward each neighbour. After fill_ghosts every local plane
// holds its global plane's value; after return_ghosts each edge plane holds what the neighbour wrote into
// its ghosts and the inner planes are untouched. Prints "slab exchange passed" on rank 0, or exits with 1
// naming the first wrong cell.
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
int check_field(const sabo::MpiWorld& world, const sabo::parallel::SlabPartition& slabs, int ghosts) {
    const int rank = world.rank(), n = slabs.end(rank) - slabs.begin(rank), x0 = slabs.begin(rank);
    const bool has_left = rank > 0, has_right = rank + 1 < world.size();
    sabo::parallel::SlabLayout layout{n, ghosts, 5, 3, static_cast<std::size_t>(n + 2 * ghosts + 3),
                                      0};  // padded
    layout.plane = layout.row * layout.ny + 7;
    const T untouched = static_cast<T>(-1);
    std::vector<T> field(layout.plane * layout.nz, untouched);
    sabo::parallel::SlabExchange exchange(world, layout);
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

}  // namespace

int main(int argc, char** argv) {
    const sabo::MpiWorld world(argc, argv);
    const sabo::parallel::SlabPartition slabs(12, world.size(), 2);
    int failed = 0;
    for (const int ghosts : {1, 2})
        failed += check_field<double>(world, slabs, ghosts) + check_field<float>(world, slabs, ghosts) +
                  check_field<std::int32_t>(world, slabs, ghosts);
    const auto total = world.sum(failed);
    if (world.rank() == 0 && total == 0) std::printf("slab exchange passed on %d rank(s)\n", world.size());
    return total == 0 ? 0 : 1;
}
