// SPDX-License-Identifier: MIT
// The grains of a coupled run divided among MPI ranks that cover a neighbour's lattice cells
// (docs/scaling.md, "Grains in the fluid, divided"). The lattice and the grains share the slab faces; a grain
// belongs to the rank of its centre, but its sphere may reach into the lattice of a neighbour: its own
// planes, which only it steps for real, or its ghost planes, which it steps too so that what streams from
// them into its own planes is right. Every lattice step each rank sends its neighbours the own grains whose
// sphere reaches into their lattice (centre, v(t), ω(t), radius); the neighbour finds the cells they cover
// among its own grains' (the deeper grain keeps a shared cell, as in an undivided run), steps its lattice
// with them, and returns the drag and torque they received in its own planes; each owner adds that to what
// its grains received at home. A grain's force is then the undivided run's, summed in another order.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mpi_world.h"
#include "coupling/grain_fluid_coupling.h"
#include "dem/dem_solver.h"

namespace sabo::parallel {

class GrainVisitors {
  public:
    explicit GrainVisitors(const MpiWorld& world) : world_(world) {}

    // Sends the own grains of `grains` whose sphere reaches below `lo` (into the left neighbour's lattice,
    // its ghost planes included) or above `hi` (the right one's) to that neighbour, and receives theirs.
    void send(const dem::DemSolver& grains, double lo, double hi);
    // The neighbours' grains that arrived (the left neighbour's, then the right one's).
    [[nodiscard]] std::span<const coupling::VisitingGrain> arrived() const { return arrived_; }
    // `force`, `torque`: the fluid's on the own grains (the first own_count() entries) and then on the
    // arrived grains. Sends the arrived grains' back to their owners and receives the own grains' from
    // the neighbours they visited: forces() and torques() are then the fluid's on every mobile grain of
    // `grains` (ghosts: none, their owner has them).
    void gather_forces(std::span<const Vec3> force, std::span<const Vec3> torque,
                       const dem::DemSolver& grains);
    [[nodiscard]] std::span<const Vec3> forces() const { return force_; }
    [[nodiscard]] std::span<const Vec3> torques() const { return torque_; }
    // Seconds spent in the exchanges (waiting for the neighbours included).
    [[nodiscard]] double exchange_seconds() const { return exchanging_; }

  private:
    [[nodiscard]] int left() const { return world_.rank() - 1; }
    [[nodiscard]] int right() const { return world_.rank() + 1 < world_.size() ? world_.rank() + 1 : -1; }
    struct Load {
        Vec3 force, torque;
    };
    const MpiWorld& world_;
    std::vector<std::uint32_t> sent_left_, sent_right_;  // own grains sent
    std::vector<coupling::VisitingGrain> out_, arrived_;
    std::size_t from_left_ = 0;  // arrived_ from the left neighbour (the first ones)
    std::vector<std::byte> received_;
    std::vector<Load> loads_out_, loads_in_;
    std::vector<Vec3> force_, torque_;
    double exchanging_ = 0.0;
};

}  // namespace sabo::parallel
