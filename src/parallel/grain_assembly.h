// SPDX-License-Identifier: MIT
// The grains of a run divided among MPI ranks seen whole (dem/grain_view.h): every rank's own grains gathered
// in the order of their global ids, the fixed spheres' and walls' contact forces summed over the ranks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/mpi_world.h"
#include "core/vec3.h"
#include "dem/dem_solver.h"
#include "dem/grain_view.h"

namespace sabo::parallel {

// The buffers of a divided run's views (none are used on one process).
class GrainAssembly {
  public:
    // Every rank's own grains gathered, the fixed spheres and the walls with the forces of the last step
    // summed over the ranks (contact_forces() refreshes them).
    [[nodiscard]] dem::GrainView view(const MpiWorld& world, const dem::DemSolver& grains, std::size_t total);
    // Sums the fixed spheres' and the walls' contact forces of the last step over the ranks.
    [[nodiscard]] dem::ContactForces contact_forces(const MpiWorld& world, const dem::DemSolver& grains,
                                                    std::size_t total);

  private:
    dem::Particles whole_;
    std::vector<std::uint32_t> ids_;
    std::vector<std::pair<std::uint64_t, std::size_t>> id_order_;  // (id, place in the gathered grains)
    std::vector<Vec3> forces_, wall_forces_;  // undivided layout: mobile (zero), then fixed
    std::vector<double> sums_;
    std::vector<std::byte> mine_, all_;
};

}  // namespace sabo::parallel
