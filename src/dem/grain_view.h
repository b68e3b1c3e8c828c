// SPDX-License-Identifier: MIT
// What the analyses, frames and summaries read of the grains: every grain of the run with its synchronous
// velocities and last contact force, the fixed spheres, the walls and the forces they received, the contact
// statistics. On one process it is the solver's own state; in a run divided among MPI ranks
// (parallel/grain_assembly.h) it is assembled on every rank from all ranks' grains (mobile grains in the
// order of their global ids) — a collective call that every rank makes at the same point of the run.
#pragma once
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/vec3.h"
#include "dem/dem_solver.h"

namespace sabo::dem {

struct GrainView {
    double time = 0.0;
    const Particles& particles;             // mobile grains, then the fixed spheres
    const std::vector<std::uint32_t>& ids;  // each mobile grain's index in the release
    const std::vector<Wall>& walls;
    const std::vector<Vec3>& wall_forces;  // N, the last step's
    ContactStats stats;                    // the last step's
    double elastic_energy = 0.0;           // J
    double max_overlap_seen = 0.0;         // the largest δ/d so far
    std::size_t list_builds = 0;
    [[nodiscard]] KineticEnergy kinetic_energy() const { return particles.kinetic_energies(); }
};

// The contact forces of the last step on every particle (the fixed spheres' are what the barrier analyses
// read; mobile grains of a divided run: zero) and on the walls, in the undivided run's order.
struct ContactForces {
    std::span<const Vec3> particles, walls;
};

}  // namespace sabo::dem
