// SPDX-License-Identifier: MIT
// The domain a run steps: where the lattice sits in the case's frame, and how a run divided among MPI ranks
// cuts it into slabs along x (docs/scaling.md). Every layer above reads the division through it.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "core/mpi_world.h"
#include "core/vec3.h"
#include "lbm/fluid_lattice.h"
#include "parallel/fluid_halo.h"
#include "parallel/slab_partition.h"

namespace sabo::parallel {

// Where the lattice sits in the case's frame: cell (x, y, z) has its centre at origin + (x+½, y+½, z+½) Δx;
// and, for a run divided among MPI ranks, the one place that knows how (docs/scaling.md): the lattice cut
// into slabs along x, this rank's slab as its lattice stores it (x local) and the halo of ghost planes.
struct Domain {
    Vec3 origin{};                    // m, the whole lattice's lower corner
    double dx = 0.0;                  // m, lattice spacing (0: no lattice)
    Vec3 box{};                       // m, extent of the lattice (or of the grains' container)
    const MpiWorld* world = nullptr;  // the ranks of a divided run (none: one process)
    std::vector<int> cuts{};          // rank r owns global planes [cuts[r], cuts[r + 1]) (empty: undivided)
    LocalSlab slab{};
    HaloSettings halo = HaloSettings::with_free_surface();
    std::uint64_t rebalance_every = 200;  // lattice steps between moves of the slab faces (0: never)
    double fed_radius_max = 0.0;          // m, the largest radius of the grains an inflow feeds (0: none fed)

    // Cuts a lattice of `planes` planes into equal slabs among the world's ranks (one rank: undivided).
    void divide(const MpiWorld& ranks, int planes) {
        if (ranks.size() < 2) return;
        const SlabPartition partition(planes, ranks.size(), halo.ghosts);
        world = &ranks;
        cuts = partition.cuts();
        slab = partition.local(ranks.rank(), halo.ghosts);
    }
    // Divides grains alone among the world's ranks (their slabs: parallel::GrainHalo; one rank: undivided).
    void divide_grains(const MpiWorld& ranks) {
        if (ranks.size() > 1) world = &ranks;
    }
    // x below which a sphere reaches into the left neighbour's lattice, and above which into the right
    // one's (their ghost planes included), m.
    [[nodiscard]] std::pair<double, double> neighbours_reach() const {
        const auto r = static_cast<std::size_t>(world->rank());
        return {origin.x + (cuts[r] + halo.ghosts) * dx, origin.x + (cuts[r + 1] - halo.ghosts) * dx};
    }
    // x of the faces between the lattice's slabs, m (grains in the fluid share them).
    [[nodiscard]] std::vector<double> face_positions() const {
        std::vector<double> faces;
        for (std::size_t r = 1; r + 1 < cuts.size(); ++r) faces.push_back(origin.x + cuts[r] * dx);
        return faces;
    }
    [[nodiscard]] bool divided() const { return world != nullptr; }
    [[nodiscard]] int ranks() const { return divided() ? world->size() : 1; }
    // The rank that writes the run's files (series, summary, report): the first.
    [[nodiscard]] bool writes_outputs() const { return !divided() || world->rank() == 0; }
    // A value summed / the largest over the ranks (the value itself when undivided).
    [[nodiscard]] double sum(double value) const { return divided() ? world->sum_real(value) : value; }
    [[nodiscard]] double max(double value) const { return divided() ? world->max_real(value) : value; }
    // Whether `flag` holds on some rank.
    [[nodiscard]] bool any(bool flag) const { return divided() ? world->max(flag ? 1 : 0) != 0 : flag; }
    // The rank's lattice of the whole one `shape`.
    [[nodiscard]] lbm::GridShape local_shape(const lbm::GridShape& shape) const {
        return divided() ? slab_shape(shape, slab) : shape;
    }
    // The rank's lattice of the whole one `shape`, which knows its own planes (the fill and the barrier's
    // cells of a case are then set in global coordinates: global_x()).
    template <class Real>
    [[nodiscard]] std::unique_ptr<lbm::FluidLattice<Real>> make_lattice(const lbm::GridShape& shape,
                                                                        const lbm::Rheology& rheology) const {
        auto lattice = std::make_unique<lbm::FluidLattice<Real>>(local_shape(shape), rheology);
        if (divided()) lattice->set_slab({slab.own_begin, slab.own_end, slab.first_global_x, {}});
        return lattice;
    }
    // Global x of the rank's local plane x.
    [[nodiscard]] int global_x(int x) const { return x + slab.first_global_x; }
    [[nodiscard]] Vec3 cell_centre(int x, int y, int z) const {
        return origin + Vec3{(global_x(x) + 0.5) * dx, (y + 0.5) * dx, (z + 0.5) * dx};
    }
};

}  // namespace sabo::parallel
