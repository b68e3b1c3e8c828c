// SPDX-License-Identifier: MIT
#include "app/high_compaction.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "analysis/stop_detector.h"
#include "dem/dem_solver.h"

namespace sabo::app {

dem::Particles presettle(const PreparedCase& pc) {
    const auto& scene = pc.scene;
    std::vector<dem::Wall> walls = scene.walls;
    walls.push_back(dem::Wall::plane("temporary_barrier", {scene.release.hi.x + 0.005, 0, 0}, {-1, 0, 0}));
    dem::DemSolver solver(scene.particles, walls, pc.dem.laws, scene.gravity, pc.dem.dt, pc.dem.skin);
    solver.set_rolling_sweeps(pc.dem.rolling_sweeps);
    solver.set_reorder_interval(pc.dem.reorder_interval);
    analysis::StopDetector stop(pc.analysis.stop_threshold, pc.analysis.stop_hold);
    const auto every = std::max<std::uint64_t>(1, std::llround(pc.series_interval / pc.dem.dt));
    spdlog::info("high compaction: settling the block against a temporary barrier at X = {:.3f} m",
                 scene.release.hi.x + 0.005);
    bool settled = false;
    while (solver.time() < scene.release.settle_max_time && !settled) {
        solver.step();
        if (solver.steps() % every == 0) {
            const auto ke = solver.kinetic_energy();
            settled = stop.sample(solver.time(), ke.translational + ke.rotational);
        }
    }
    dem::Particles p = solver.particles();
    for (std::size_t i = 0; i < p.n_mobile; ++i) p.v[i] = p.w[i] = {};
    double front = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) front = std::max(front, p.x[i].x + p.r[i]);
    if (settled) {
        spdlog::info("high compaction: settled after {:.2f} s; block front at X = {:.3f} m; barrier removed",
                     solver.time(), front);
    } else {
        spdlog::warn(
            "high compaction: not at rest after release.settle_max_time_s = {:.3g} s; starting anyway",
            scene.release.settle_max_time);
    }
    return p;
}

}  // namespace sabo::app
