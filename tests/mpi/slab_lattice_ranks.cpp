// SPDX-License-Identifier: MIT
// A lattice of bulk fluid divided into slabs along x, run on 1, 2 and 3 processes (`mpiexec -n N`; ctest
// slab_lattice_*): walls at both x ends, periodic in y and z, a disturbed density and velocity field and a
// body force along y, so that pressure waves and shear cross the slab faces. Each rank steps its planes
// plus `ghosts` ghost planes toward each neighbour and, after every odd step of the AA pattern, refreshes
// the ghosts' 19 populations and τ from the neighbours (parallel::LatticeHalo, docs/scaling.md); its own
// planes must then equal the undivided lattice's, which every rank also runs, bit for bit (float64 and
// float32 storage, Newtonian and Bingham). Prints "slab lattice passed" on rank 0 or exits with 1 naming the
// first differing cell.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "core/mpi_world.h"
#include "lbm/fluid_lattice.h"
#include "parallel/fluid_halo.h"

namespace {

using sabo::Vec3;
using sabo::lbm::FluidLattice;

constexpr int nx = 24, ny = 4, nz = 5, steps = 80;

// The initial state at global plane x: a density bump and a sheared velocity.
void fill(auto& lattice, int x_local, int x_global) {
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y) {
            const double phase = 2.0 * std::numbers::pi * (x_global + 0.5) / nx;
            lattice.set_fluid(x_local, y, z, 1.0 + 0.02 * std::sin(phase + 0.4 * y),
                              {0.01 * std::cos(phase), 0.02 * std::sin(phase + 0.3 * z), 0.005 * y});
        }
}

template <class Real>
int check(const sabo::MpiWorld& world, const sabo::lbm::Rheology& rheology, int ghosts, const char* name) {
    const sabo::lbm::GridShape whole{nx, ny, nz, {false, true, true}};
    FluidLattice<Real> reference(whole, rheology);
    for (int x = 0; x < nx; ++x) fill(reference, x, x);
    reference.set_acceleration({0.0, 1e-5, 0.0});
    reference.prepare();

    const sabo::parallel::HaloSettings halo{.ghosts = ghosts};
    const sabo::parallel::LocalSlab slabs = sabo::parallel::equal_slab(world, nx, halo);
    FluidLattice<Real> slab(sabo::parallel::slab_shape(whole, slabs), rheology);
    sabo::parallel::LatticeHalo<Real> ghosts_of_slab(world, slab, slabs, halo);
    for (int x = 0; x < slabs.planes; ++x) fill(slab, x, x + slabs.first_global_x);
    slab.set_acceleration({0.0, 1e-5, 0.0});
    slab.prepare();
    ghosts_of_slab.prepare();
    for (int s = 0; s < steps; ++s) {
        reference.step();
        slab.step();
        ghosts_of_slab.after_step();
    }
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = slabs.own_begin; x < slabs.own_end; ++x) {
                double rho_a = 0, rho_b = 0;
                Vec3 u_a, u_b;
                slab.moments(slab.index(x, y, z), rho_a, u_a);
                reference.moments(reference.index(x + slabs.first_global_x, y, z), rho_b, u_b);
                if (rho_a != rho_b || u_a.x != u_b.x || u_a.y != u_b.y || u_a.z != u_b.z) {
                    std::fprintf(
                        stderr,
                        "rank %d, %s, %d ghosts: cell (%d, %d, %d): rho %.17g vs %.17g, u_y %.17g vs "
                        "%.17g\n",
                        world.rank(), name, ghosts, x + slabs.first_global_x, y, z, rho_a, rho_b, u_a.y,
                        u_b.y);
                    return 1;
                }
            }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const sabo::MpiWorld world(argc, argv);
    sabo::lbm::Rheology newtonian;
    newtonian.tau = 0.7;
    sabo::lbm::Rheology bingham;
    bingham.bingham = true;
    bingham.nu_plastic = 0.05;
    bingham.yield = 1e-5;
    const int ghosts = argc > 1 ? std::atoi(argv[1]) : 2;
    int failed = 0;
    failed += check<double>(world, newtonian, ghosts, "float64 Newtonian");
    failed += check<float>(world, newtonian, ghosts, "float32 Newtonian");
    failed += check<double>(world, bingham, ghosts, "float64 Bingham");
    const auto total = world.sum(failed);
    if (world.rank() == 0 && total == 0)
        std::printf("slab lattice passed on %d rank(s), %d ghost planes\n", world.size(), ghosts);
    return total == 0 ? 0 : 1;
}
