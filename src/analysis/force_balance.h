// SPDX-License-Identifier: MIT
// Where the deposit's down-slope weight goes: the X (down-slope) components of the forces the channel's
// walls receive from the grains, by wall kind, beside the barrier's. At rest the grains' weight along X
// equals the barrier's force plus these (docs/analysis.md, "Force balance").
#pragma once
#include <span>

#include "core/vec3.h"
#include "dem/walls.h"

namespace sabo::analysis {

struct WallLoads {
    double bed_x = 0.0;         // N, the bed ("bed", and a channel mesh's bed relief "bed_mesh_*")
    double side_walls_x = 0.0;  // N, the two side walls ("side_*")
    double other_x = 0.0;       // N, ceiling and end walls (every other wall that is not a barrier element)
};

// `forces`: the force each wall received in the last step (DemSolver::wall_forces()), aligned with `walls`.
[[nodiscard]] WallLoads wall_loads(std::span<const dem::Wall> walls, std::span<const Vec3> forces);

}  // namespace sabo::analysis
