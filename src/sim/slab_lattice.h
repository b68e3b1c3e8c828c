// SPDX-License-Identifier: MIT
// A lattice of bulk fluid (no free surface, no grains yet) divided into slabs along x among the ranks
// (docs/scaling.md, "Bulk fluid, as built"): this rank's lattice holds its planes and `ghosts` ghost planes
// toward each neighbour, a wall beyond the outer ghost, and is stepped whole by the unchanged kernel; after
// every odd step of the AA pattern the ghosts' 19 populations and relaxation times are refreshed from the
// neighbours. With 2 ghost planes the own planes then step bit for bit like the undivided lattice.
#pragma once
#include <chrono>
#include <span>
#include <vector>

#include "core/error.h"
#include "core/mpi_world.h"
#include "lbm/fluid_lattice.h"
#include "sim/slab_exchange.h"
#include "sim/slab_partition.h"

namespace sabo::sim {

template <class Real>
class SlabLattice {
  public:
    // This rank's equal share of `whole` (closed in x: walls at both ends).
    SlabLattice(const MpiWorld& world, const lbm::GridShape& whole, const lbm::Rheology& rheology,
                int ghosts = 2)
        : SlabLattice(world, whole, rheology, ghosts, SlabPartition(whole.nx, world.size(), ghosts)) {}

    // The rank's lattice: local planes [0, local_planes()), set up by the caller (global_x() of each) and
    // prepared before the first step.
    [[nodiscard]] lbm::FluidLattice<Real>& lattice() { return lattice_; }
    [[nodiscard]] const lbm::FluidLattice<Real>& lattice() const { return lattice_; }
    [[nodiscard]] int local_planes() const { return lattice_.shape().nx; }
    [[nodiscard]] int global_x(int local_x) const { return local_x + first_global_; }
    // The rank's own planes, local x in [own_begin(), own_end()).
    [[nodiscard]] int own_begin() const { return exchange_.first_own(); }
    [[nodiscard]] int own_end() const { return exchange_.first_own() + planes_; }

    void step() {
        lattice_.step();
        if (lattice_.steps() % 2 == 0) {  // the step just done was odd
            const auto start = std::chrono::steady_clock::now();
            exchange_.fill_ghosts(std::span<const std::span<Real>>(state_));
            exchanging_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
    }
    // Wall-clock seconds this rank spent refreshing its ghosts (waiting for a neighbour included).
    [[nodiscard]] double exchange_seconds() const { return exchanging_; }

  private:
    SlabLattice(const MpiWorld& world, const lbm::GridShape& whole, const lbm::Rheology& rheology, int ghosts,
                const SlabPartition& slabs)
        : planes_(slabs.end(world.rank()) - slabs.begin(world.rank())),
          lattice_(local_shape(world, whole, ghosts, planes_), rheology),
          exchange_(world,
                    {planes_, ghosts, whole.ny, whole.nz, row(), row() * static_cast<std::size_t>(whole.ny)},
                    lbm::Q + 1),
          first_global_(slabs.begin(world.rank()) - exchange_.first_own()) {
        // what a step leaves in the ghosts to be refreshed: the 19 populations and τ, one message per face
        for (int i = 0; i < lbm::Q; ++i) state_.push_back(lattice_.population_slots(i));
        state_.push_back(lattice_.relaxation_times());
    }
    static lbm::GridShape local_shape(const MpiWorld& world, const lbm::GridShape& whole, int ghosts,
                                      int planes) {
        if (whole.periodic[0])
            throw InputError("a lattice divided into slabs along x must be closed in x (walls at both ends)");
        const int toward_neighbours = (world.rank() > 0 ? 1 : 0) + (world.rank() + 1 < world.size() ? 1 : 0);
        return {planes + ghosts * toward_neighbours,
                whole.ny,
                whole.nz,
                {false, whole.periodic[1], whole.periodic[2]}};
    }
    [[nodiscard]] std::size_t row() const { return lbm::FluidLattice<Real>::row_stride(lattice_.shape().nx); }

    int planes_;
    lbm::FluidLattice<Real> lattice_;
    SlabExchange exchange_;
    int first_global_;
    std::vector<std::span<Real>> state_;
    double exchanging_ = 0.0;
};

}  // namespace sabo::sim
