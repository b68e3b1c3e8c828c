// SPDX-License-Identifier: MIT
#include "analysis/force_balance.h"

namespace sabo::analysis {

WallLoads wall_loads(std::span<const dem::Wall> walls, std::span<const Vec3> forces) {
    WallLoads loads;
    for (std::size_t w = 0; w < walls.size() && w < forces.size(); ++w) {
        const dem::Wall& wall = walls[w];
        if (wall.barrier) continue;
        const double fx = forces[w].x;
        if (wall.name == "bed" || wall.name.starts_with("bed_mesh_"))  // (the plane, a mesh's bed relief)
            loads.bed_x += fx;
        else if (wall.name.starts_with("side_"))
            loads.side_walls_x += fx;
        else
            loads.other_x += fx;
    }
    return loads;
}

}  // namespace sabo::analysis
