// SPDX-License-Identifier: MIT
// The ghost-plane exchange between slabs, run on 1, 2 and 3 processes (`mpiexec -n N`; ctest
// slab_exchange_*): each rank's slab of a 12-plane channel holds, in every cell, a value naming its global
// plane, y and z. After fill_ghosts each ghost holds its neighbour's edge plane; after return_ghosts each
// edge plane holds what the neighbour wrote into its ghost; the domain's ends are never touched. Prints
// "slab exchange passed" on rank 0, or exits with 1 naming the first wrong cell.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/mpi_world.h"
#include "sim/slab_exchange.h"
#include "sim/slab_partition.h"

namespace {

template <class T>
T value(int global_x, int y, int z) {
    return static_cast<T>(1000 * global_x + 10 * y + z);
}

template <class T>
int check_field(const sabo::MpiWorld& world, const sabo::sim::SlabPartition& slabs) {
    const int rank = world.rank(), n = slabs.end(rank) - slabs.begin(rank), x0 = slabs.begin(rank);
    sabo::sim::SlabLayout layout{n, 5, 3, static_cast<std::size_t>(n + 2 + 3), 0};  // a padded row
    layout.plane = layout.row * layout.ny + 7;
    const T untouched = static_cast<T>(-1);
    std::vector<T> field(layout.plane * layout.nz, untouched);
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y)
            for (int x = 1; x <= n; ++x) field[layout.index(x, y, z)] = value<T>(x0 + x - 1, y, z);
    sabo::sim::SlabExchange exchange(world, layout);
    auto expect = [&](int x, int y, int z, T want, const char* what) {
        if (field[layout.index(x, y, z)] == want) return true;
        std::fprintf(stderr, "rank %d: %s: local plane %d (%d, %d) holds %g, expected %g\n", rank, what, x, y,
                     z, static_cast<double>(field[layout.index(x, y, z)]), static_cast<double>(want));
        return false;
    };
    exchange.fill_ghosts(std::span(field));
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y) {
            const T left = rank > 0 ? value<T>(x0 - 1, y, z) : untouched;
            const T right = rank + 1 < world.size() ? value<T>(x0 + n, y, z) : untouched;
            if (!expect(0, y, z, left, "fill, left ghost") ||
                !expect(n + 1, y, z, right, "fill, right ghost"))
                return 1;
        }
    // what a step "wrote" into the ghosts: minus their global plane's value
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y) {
            field[layout.index(0, y, z)] = -value<T>(x0 - 1, y, z);
            field[layout.index(n + 1, y, z)] = -value<T>(x0 + n, y, z);
        }
    exchange.return_ghosts(std::span(field));
    for (int z = 0; z < layout.nz; ++z)
        for (int y = 0; y < layout.ny; ++y) {
            const T first = rank > 0 ? -value<T>(x0, y, z) : value<T>(x0, y, z);
            const T last = rank + 1 < world.size() ? -value<T>(x0 + n - 1, y, z) : value<T>(x0 + n - 1, y, z);
            if (!expect(1, y, z, first, "return, first plane") ||
                !expect(n, y, z, last, "return, last plane"))
                return 1;
            for (int x = 2; x < n; ++x)
                if (!expect(x, y, z, value<T>(x0 + x - 1, y, z), "return, inner plane")) return 1;
        }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const sabo::MpiWorld world(argc, argv);
    const sabo::sim::SlabPartition slabs(12, world.size(), 2);
    const int failed = check_field<double>(world, slabs) + check_field<float>(world, slabs) +
                       check_field<std::int32_t>(world, slabs);
    const auto total = world.sum(failed);
    if (world.rank() == 0 && total == 0) std::printf("slab exchange passed on %d rank(s)\n", world.size());
    return total == 0 ? 0 : 1;
}
