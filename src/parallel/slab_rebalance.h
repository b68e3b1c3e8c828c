// SPDX-License-Identifier: MIT
// Slab faces that follow the work (docs/scaling.md, "Faces that follow the work"): every few hundred steps
// each rank prices its own planes, the ranks place new faces on the whole channel's costs
// (SlabPartition::balanced), each face moving toward its new place but not past the old faces beside it, and
// the planes that change owner travel to their new rank with their whole state. The price of a plane counts
// its cells by type with weights measured on the lattice's kernels (an interface cell costs several bulk
// ones; a gas cell is skipped almost for free): a model, not a clock, so that a run's partition — and with it
// the round-off of its sums over the ranks — is the same every time it is run.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "core/mpi_world.h"
#include "core/vec3.h"
#include "lbm/fluid_lattice.h"
#include "parallel/slab_partition.h"

namespace sabo::parallel {

// Per cell; obstacles cost nothing. The interface weight from the ranks' measured stepping times: the
// slowest rank's time over the mean fell from 1.20 to 1.08 over weights 4 → 24 (C5 fluid-only, scaled; flat
// from 16 on), and from 1.11 to 1.05 (dam break) and 1.17 to 1.09 (C5 coupled, scaled) over 4 → 16
// (bench/RESULTS.md) — an interface cell's mass exchange, reconstruction and conversions read scattered
// memory. The gas weight from a least-squares fit of the ranks' stepping times per 200 steps to their cells'
// counts (1909-grain coupled run, 2 ranks: interface 16.0, gas 0.037; docs/scaling.md).
struct PlaneCostWeights {
    double fluid = 1.0, interface = 16.0, gas = 0.04;
    double grain = 4.0;  // per grain and DEM step (a grain in the fluid: its contacts and its cells)
};

// The price of each own plane of `lattice`, in order.
template <class Real>
[[nodiscard]] std::vector<double> own_plane_costs(const lbm::FluidLattice<Real>& lattice,
                                                  const PlaneCostWeights& w = {}) {
    const auto& sh = lattice.shape();
    std::vector<double> cost(static_cast<std::size_t>(lattice.own_end() - lattice.own_begin()), 0.0);
    for (int z = 0; z < sh.nz; ++z)
        for (int y = 0; y < sh.ny; ++y)
            for (int x = lattice.own_begin(); x < lattice.own_end(); ++x) {
                const lbm::CellType t = lattice.type(lattice.index(x, y, z));
                cost[static_cast<std::size_t>(x - lattice.own_begin())] +=
                    t == lbm::CellType::fluid
                        ? w.fluid
                        : (t == lbm::CellType::interface ? w.interface : (t == lbm::CellType::gas ? w.gas : 0.0));
            }
    return cost;
}

// Adds `per_grain` to the price of the own plane that holds each grain's centre (`x`, m: the first `own`
// of them; a centre outside the own planes counts in the nearest one). The lattice's local plane 0 starts at
// x = `plane0_x`, m, planes `dx` apart.
template <class Real>
void add_grain_costs(std::vector<double>& costs, const lbm::FluidLattice<Real>& lattice,
                     std::span<const Vec3> x, std::size_t own, double plane0_x, double dx, double per_grain) {
    for (std::size_t i = 0; i < own; ++i) {
        const auto plane = static_cast<int>(std::floor((x[i].x - plane0_x) / dx));
        costs[static_cast<std::size_t>(std::clamp(plane, lattice.own_begin(), lattice.own_end() - 1) -
                                       lattice.own_begin())] += per_grain;
    }
}

// The faces after this rebalancing: every rank's plane costs gathered, the balanced faces, each face moved
// toward its place but not past the old faces beside it (so that each plane a rank gains is held by the
// neighbour it comes from), every slab at least `thinnest` planes thick (twice the ghost planes; grains in
// the fluid: their contacts' reach too). The old faces when the move would lower the dearest slab's cost by
// less than `min_gain`: a move costs about ten steps' work (a copy of the slab, its links found again, a new
// halo) and the prices of slabs whose steps take equal times differ by 5-10 %, so a smaller predicted gain
// lies within the model's error and does not repay the move (docs/scaling.md). Collective.
[[nodiscard]] std::vector<int> rebalanced_cuts(const MpiWorld& world, const std::vector<int>& cuts,
                                               std::span<const double> own_costs, int thinnest,
                                               double min_gain = 0.10);

// The rank's lattice for the faces `to` (from `from`), its planes moved from `old` and from the neighbours;
// `old`'s ghosts must be exact (just refreshed). Built in `spare`'s memory where one is given (a lattice no
// longer needed: the one the last move replaced). Collective.
template <class Real>
[[nodiscard]] std::unique_ptr<lbm::FluidLattice<Real>> moved_lattice(
    const MpiWorld& world, const lbm::FluidLattice<Real>& old, const std::vector<int>& from,
    const std::vector<int>& to, int ghosts, std::unique_ptr<lbm::FluidLattice<Real>> spare = nullptr);

// An empty lattice (gas, no elements) of the rank's slab of faces `cuts`, of `shape`'s cross-section and
// rheology (in `spare`'s memory where one is given): what a checkpoint written after the faces moved is read
// into.
template <class Real>
[[nodiscard]] std::unique_ptr<lbm::FluidLattice<Real>> slab_lattice(
    const MpiWorld& world, const lbm::FluidLattice<Real>& shape, const std::vector<int>& cuts, int ghosts,
    std::unique_ptr<lbm::FluidLattice<Real>> spare = nullptr);

}  // namespace sabo::parallel
