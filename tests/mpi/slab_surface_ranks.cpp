// SPDX-License-Identifier: MIT
// A free-surface dam break divided into slabs along x, run on 1, 2 and 3 processes (`mpiexec -n N`; ctest
// slab_surface_*): a column of fluid at the left wall, with a bubble of gas in it astride a slab face, falls
// under gravity, runs along the floor across the slab faces and splashes up the right wall. Cells fill and
// empty across the faces, and the bubble's collapse and the spray leave excess mass with no interface
// neighbour, which goes to the whole surface, every slab's. Each rank steps its planes plus ghost planes
// toward each neighbour and refreshes the ghosts' state every `interval` steps (parallel::LatticeHalo);
// its own planes must then equal the undivided lattice's, which every rank also runs, bit for bit: cell
// types, λ, τ, masses, densities and velocities (float64 and float32 storage, Newtonian and Bingham), and so
// must its ghost planes once refreshed whole. Then again with the closed pockets' deficit taken within 3
// cells of them (FluidLattice::set_pocket_reach), the bubble's among them, with the deeper halo that asks
// for. Usage: slab_surface_ranks [GHOSTS [INTERVAL]] (default: parallel::HaloSettings::with_free_surface()
// for each reach; GHOSTS: for both). Prints "slab surface passed" on rank 0 or exits with 1 naming the first
// differing cell.
#include <cstdio>
#include <cstdlib>

#include "core/mpi_world.h"
#include "lbm/fluid_lattice.h"
#include "parallel/fluid_halo.h"

namespace {

using sabo::Vec3;
using sabo::lbm::CellType;
using sabo::lbm::FluidLattice;

constexpr int nx = 42, ny = 5, nz = 18, steps = 600, compare_every = 25;

// The initial state at global plane x: fluid for x < 14 and z < 13 (a little deeper at higher y, so the
// flow is three-dimensional) but for a bubble around (13.5, 2, 5).
void fill(auto& lattice, int x_local, int x) {
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y) {
            const bool bubble = (x == 13 || x == 14) && y >= 1 && y <= 3 && z >= 4 && z <= 6;
            if (x < 15 && z < 13 + y / 2 && !bubble) lattice.set_fluid(x_local, y, z, 1.0, {});
        }
}

struct Tally {
    std::size_t orphan_cells = 0, filled = 0, emptied = 0, pocket_cells = 0;
};

template <class Real>
int check(const sabo::MpiWorld& world, const sabo::lbm::Rheology& rheology,
          const sabo::parallel::HaloSettings& halo, int pocket_reach, const char* name, Tally& tally) {
    const sabo::lbm::GridShape whole{nx, ny, nz, {false, false, false}};
    const Vec3 gravity{0.0, 0.0, -4e-4};
    FluidLattice<Real> reference(whole, rheology);
    for (int x = 0; x < nx; ++x) fill(reference, x, x);
    reference.set_acceleration(gravity);
    reference.set_pocket_reach(pocket_reach);
    reference.prepare();

    const sabo::parallel::LocalSlab slabs = sabo::parallel::equal_slab(world, nx, halo);
    FluidLattice<Real> slab(sabo::parallel::slab_shape(whole, slabs), rheology);
    sabo::parallel::LatticeHalo<Real> ghosts(world, slab, slabs, halo);
    for (int x = 0; x < slabs.planes; ++x) fill(slab, x, x + slabs.first_global_x);
    slab.set_acceleration(gravity);
    slab.set_pocket_reach(pocket_reach);
    slab.prepare();
    ghosts.prepare();
    for (int s = 1; s <= steps; ++s) {
        reference.step();
        slab.step();
        ghosts.after_step();
        tally.orphan_cells += reference.surface_stats().orphan_excess_cells;
        tally.filled += reference.surface_stats().filled;
        tally.emptied += reference.surface_stats().emptied;
        tally.pocket_cells += reference.surface_stats().pocket_cells;
        if (s % compare_every != 0) continue;
        // the ghost planes too, refreshed whole (a step's refresh leaves out the rows no step reads)
        ghosts.refresh_whole();
        int bad = 0;
        for (int z = 0; z < nz && bad == 0; ++z)
            for (int y = 0; y < ny && bad == 0; ++y)
                for (int x = 0; x < slab.shape().nx && bad == 0; ++x) {
                    const std::size_t a = slab.index(x, y, z),
                                      b = reference.index(x + slabs.first_global_x, y, z);
                    double rho_a = 0, rho_b = 0;
                    Vec3 u_a, u_b;
                    const bool own = x >= slabs.own_begin && x < slabs.own_end;
                    const bool wet = slab.type(a) == CellType::fluid || slab.type(a) == CellType::interface;
                    // (a ghost cell's moments may read the wall beyond the ghosts: its own slots are
                    // compared)
                    bool slots_differ = false;
                    for (int i = 0; i < sabo::lbm::Q && !own; ++i)
                        slots_differ |= slab.population_slots(i)[a] != reference.population_slots(i)[b];
                    if (own && wet && slab.type(a) == reference.type(b)) {
                        slab.moments(a, rho_a, u_a);
                        reference.moments(b, rho_b, u_b);
                    }
                    if (slab.type(a) != reference.type(b) || slab.fill(a) != reference.fill(b) ||
                        slab.tau(a) != reference.tau(b) || slab.masses()[a] != reference.masses()[b] ||
                        slots_differ || rho_a != rho_b || u_a.x != u_b.x || u_a.y != u_b.y ||
                        u_a.z != u_b.z) {
                        std::fprintf(
                            stderr,
                            "rank %d, %s, pocket reach %d, %d ghosts every %d steps, step %d: cell (%d, %d, "
                            "%d): type %d vs %d, fill %.17g vs %.17g, rho %.17g vs %.17g\n",
                            world.rank(), name, pocket_reach, halo.ghosts, halo.refresh_interval, s,
                            x + slabs.first_global_x, y, z, static_cast<int>(slab.type(a)),
                            static_cast<int>(reference.type(b)), slab.fill(a), reference.fill(b), rho_a,
                            rho_b);
                        bad = 1;
                    }
                }
        // stop together: a rank that left the loop would leave its neighbours waiting in the exchange
        if (world.sum(bad) != 0) return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const sabo::MpiWorld world(argc, argv);
    sabo::lbm::Rheology newtonian;
    newtonian.tau = 0.6;
    sabo::lbm::Rheology bingham;
    bingham.bingham = true;
    bingham.nu_plastic = 0.05;
    bingham.yield = 2e-5;
    const auto halo_for = [&](int pocket_reach) {
        sabo::parallel::HaloSettings halo = sabo::parallel::HaloSettings::with_free_surface(pocket_reach);
        if (argc > 1) halo.ghosts = std::atoi(argv[1]);
        if (argc > 2) halo.refresh_interval = std::atoi(argv[2]);
        return halo;
    };
    int failed = 0;
    for (const int reach : {0, 3}) {
        const sabo::parallel::HaloSettings halo = halo_for(reach);
        Tally tally;
        if (failed == 0) failed += check<double>(world, newtonian, halo, reach, "float64 Newtonian", tally);
        if (failed == 0) failed += check<float>(world, newtonian, halo, reach, "float32 Newtonian", tally);
        if (failed == 0) failed += check<double>(world, bingham, halo, reach, "float64 Bingham", tally);
        if (world.rank() == 0 && failed == 0)
            std::printf(
                "slab surface passed on %d rank(s), pocket reach %d, %d ghost planes refreshed every %d "
                "step(s): %zu cells filled, %zu emptied, %zu with orphan excess, %zu closed pockets' cells "
                "spread near them\n",
                world.size(), reach, halo.ghosts, halo.refresh_interval, tally.filled, tally.emptied,
                tally.orphan_cells, tally.pocket_cells);
    }
    return failed == 0 ? 0 : 1;
}
