// SPDX-License-Identifier: MIT
// Strong scaling of the bulk-fluid lattice divided into slabs (docs/scaling.md, bench/RESULTS.md): an
// NX × NY × NZ lattice of fluid (walls at the x ends, periodic in y and z, a body force along y), float64
// Newtonian, stepped STEPS times by every rank on its slab with 2 ghost planes each way (refreshed after
// each odd step). Run it as one process with OMP_NUM_THREADS threads, or under mpiexec with threads per
// rank; rank 0 prints the wall time of the steps and the million own-cell updates per second.
//   slab_lattice_bench [NX NY NZ STEPS]      (default 192 48 48 200)
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "core/mpi_world.h"
#include "lbm/fluid_lattice.h"
#include "sim/slab_exchange.h"
#include "sim/slab_partition.h"

int main(int argc, char** argv) {
    const sabo::MpiWorld world(argc, argv);
    const int nx = argc > 4 ? std::atoi(argv[1]) : 192, ny = argc > 4 ? std::atoi(argv[2]) : 48;
    const int nz = argc > 4 ? std::atoi(argv[3]) : 48, steps = argc > 4 ? std::atoi(argv[4]) : 200;
    constexpr int ghosts = 2;
    const sabo::sim::SlabPartition slabs(nx, world.size(), ghosts);
    const int rank = world.rank(), planes = slabs.end(rank) - slabs.begin(rank);
    const bool has_left = rank > 0, has_right = rank + 1 < world.size();
    const int local = planes + (has_left ? ghosts : 0) + (has_right ? ghosts : 0);
    const int x0 = slabs.begin(rank) - (has_left ? ghosts : 0);
    sabo::lbm::Rheology newtonian;
    newtonian.tau = 0.7;
    using Lattice = sabo::lbm::FluidLattice<double>;
    Lattice slab({local, ny, nz, {false, true, true}}, newtonian);
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < local; ++x) {
                const double phase = 2.0 * std::numbers::pi * (x + x0 + 0.5) / nx;
                slab.set_fluid(x, y, z, 1.0 + 0.01 * std::sin(phase), {0.01 * std::cos(phase), 0.0, 0.0});
            }
    slab.set_acceleration({0.0, 1e-6, 0.0});
    slab.prepare();
    sabo::sim::SlabExchange exchange(
        world, {planes, ghosts, ny, nz, Lattice::row_stride(local), Lattice::row_stride(local) * ny});
    // what a step leaves in the ghosts to be refreshed: the 19 populations and τ, one message per face
    std::vector<std::span<double>> state;
    for (int i = 0; i < sabo::lbm::Q; ++i) state.push_back(slab.population_slots(i));
    state.push_back(slab.relaxation_times());
    world.barrier();
    const auto start = std::chrono::steady_clock::now();
    double exchanging = 0.0;  // this rank's seconds in the exchange (waiting for the neighbour included)
    for (int s = 0; s < steps; ++s) {
        slab.step();
        if (s % 2 == 1) {
            const auto t = std::chrono::steady_clock::now();
            exchange.fill_ghosts(std::span<const std::span<double>>(state));
            exchanging += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
        }
    }
    world.barrier();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double exchanging_max =
        1e-6 * static_cast<double>(world.max(static_cast<std::int64_t>(1e6 * exchanging)));
    if (rank == 0)
        fmt::print(
            "{} rank(s), {} x {} x {} cells, {} steps: {:.3f} s, {:.1f} MLUPS (own cells); in the exchange "
            "{:.3f} s (the slowest rank)\n",
            world.size(), nx, ny, nz, steps, wall, 1e-6 * nx * ny * nz * steps / wall, exchanging_max);
    return 0;
}
