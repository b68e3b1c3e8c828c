// SPDX-License-Identifier: MIT
#include "cases/channel/presettle.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "analysis/stop_detector.h"
#include "core/error.h"
#include "dem/dem_setup.h"
#include "sim/run_loop.h"
#include "sim/simulation.h"

namespace sabo::cases {

namespace {

// Ends the settling at the complete stop of the channel case (its threshold and hold).
class SettledBlock final : public sim::Observer {
  public:
    SettledBlock(double threshold, double hold) : stop_(threshold, hold) {}
    bool sample(sim::Simulation& sim) override {
        const auto ke = sim.grains().kinetic_energy();
        return stop_.sample(sim.time(), ke.translational + ke.rotational);
    }
    [[nodiscard]] std::string phase() const override { return "high compaction"; }

  private:
    analysis::StopDetector stop_;
};

}  // namespace

dem::Particles presettle(const PreparedCase& pc, sim::RunControl& control) {
    const auto& scene = pc.scene;
    std::vector<dem::Wall> walls = scene.walls;
    walls.push_back(dem::Wall::plane("temporary_barrier", {scene.release.hi.x + 0.005, 0, 0}, {-1, 0, 0}));
    sim::Simulation sim(dem::make_solver(scene.particles, walls, scene.gravity, pc.dem));
    SettledBlock settled(pc.analysis.stop_threshold, pc.analysis.stop_hold);
    sim::Schedule at = sim::make_schedule(pc.dem.dt, scene.release.settle_max_time, pc.output.series_interval,
                                          scene.release.settle_max_time);
    at.start_outputs = false;  // the block starts at rest: the stop's hold starts at the first sample
    spdlog::info("high compaction: settling the block against a temporary barrier at X = {:.3f} m",
                 scene.release.hi.x + 0.005);
    const sim::RunEnd end = sim::run(sim, at, {&settled}, control);
    if (end.exit_code == 3) throw RunError("high compaction: " + end.failure);
    dem::Particles p = sim.grains().particles();
    for (std::size_t i = 0; i < p.n_mobile; ++i) p.v[i] = p.w[i] = {};
    double front = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) front = std::max(front, p.x[i].x + p.r[i]);
    if (end.exit_code == 130) {
        spdlog::warn("high compaction: settling stopped at t = {:.2f} s by the stop request", sim.time());
    } else if (end.ending == sim::RunEnding::complete_stop) {
        spdlog::info("high compaction: settled after {:.2f} s; block front at X = {:.3f} m; barrier removed",
                     sim.time(), front);
    } else {
        spdlog::warn(
            "high compaction: not at rest after release.settle_max_time_s = {:.3g} s; starting anyway",
            scene.release.settle_max_time);
    }
    return p;
}

}  // namespace sabo::cases
