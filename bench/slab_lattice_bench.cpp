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
#include "parallel/fluid_halo.h"

int main(int argc, char** argv) {
    const sabo::MpiWorld world(argc, argv);
    const int nx = argc > 4 ? std::atoi(argv[1]) : 192, ny = argc > 4 ? std::atoi(argv[2]) : 48;
    const int nz = argc > 4 ? std::atoi(argv[3]) : 48, steps = argc > 4 ? std::atoi(argv[4]) : 200;
    sabo::lbm::Rheology newtonian;
    newtonian.tau = 0.7;
    const sabo::lbm::GridShape whole{nx, ny, nz, {false, true, true}};
    const sabo::parallel::HaloSettings halo = sabo::parallel::HaloSettings::bulk();
    const sabo::parallel::LocalSlab slabs = sabo::parallel::equal_slab(world, nx, halo);
    sabo::lbm::FluidLattice<double> slab(sabo::parallel::slab_shape(whole, slabs), newtonian);
    sabo::parallel::LatticeHalo<double> ghosts(world, slab, slabs, halo);
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < slabs.planes; ++x) {
                const double phase = 2.0 * std::numbers::pi * (x + slabs.first_global_x + 0.5) / nx;
                slab.set_fluid(x, y, z, 1.0 + 0.01 * std::sin(phase), {0.01 * std::cos(phase), 0.0, 0.0});
            }
    slab.set_acceleration({0.0, 1e-6, 0.0});
    slab.prepare();
    ghosts.prepare();
    world.barrier();
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) {
        slab.step();
        ghosts.after_step();
    }
    world.barrier();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double exchanging_max =
        1e-6 * static_cast<double>(world.max(static_cast<std::int64_t>(1e6 * ghosts.exchange_seconds())));
    if (world.rank() == 0)
        fmt::print(
            "{} rank(s), {} x {} x {} cells, {} steps: {:.3f} s, {:.1f} MLUPS (own cells); in the exchange "
            "{:.3f} s (the slowest rank)\n",
            world.size(), nx, ny, nz, steps, wall, 1e-6 * nx * ny * nz * steps / wall, exchanging_max);
    return 0;
}
