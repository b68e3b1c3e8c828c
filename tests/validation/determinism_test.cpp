// SPDX-License-Identifier: MIT
// Same input and same thread count give the same output bit for bit; and because every grain's
// forces are summed in an order fixed by the neighbour list (own + received in ascending owner
// order, whichever path finishes the grain), 1, 2 and 3 threads give bit-identical results too.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>

#include "core/config.h"
#include "dem/dem_setup.h"
#include "scenario/channel_case.h"

namespace sabo {
namespace {

std::vector<Vec3> run_channel(int threads, int steps) {
    omp_set_num_threads(threads);
    const auto cfg = Config::from_string(R"(
[case]
end_time_s = 1.0
[channel]
slope_deg = 35.0
[release]
solid_volume_m3 = 0.25
front_x_m = 7.8
[barrier]
type = "slit"
outlet_width_over_r = 3.0
[contact]
kn_N_m = 1e6
restitution = 0.2
[contact.particle_particle]
friction_angle_deg = 30.0
)",
                                         "determinism.toml");
    const auto scene = scenario::build_channel_case(cfg);
    const auto& rel = scene.release;
    const auto dem = dem::read_dem_settings(cfg, {rel.r_min, rel.r_max, rel.density, scene.velocity_scale});
    dem::DemSolver s(scene.particles, scene.walls, dem.laws, scene.gravity, dem.dt, dem.skin);
    for (int k = 0; k < steps; ++k) s.step();
    EXPECT_GT(s.stats().contacts, 100u);
    std::vector<Vec3> state = s.particles().x;
    state.insert(state.end(), s.particles().w.begin(), s.particles().w.end());
    state.insert(state.end(), s.particles().f.begin(), s.particles().f.end());
    return state;
}

bool bit_identical(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

TEST(Determinism, RepeatRunsAndThreadCountsGiveBitIdenticalResults) {
    const int steps = 5000;  // the block reaches the barrier: walls, fixed spheres and pairs all active
    const auto one_a = run_channel(1, steps);
    const auto one_b = run_channel(1, steps);
    const auto two = run_channel(2, steps);
    const auto three = run_channel(3, steps);  // two range boundaries (more than the machine's cores)
    EXPECT_TRUE(bit_identical(one_a, one_b));
    EXPECT_TRUE(bit_identical(one_a, two));
    EXPECT_TRUE(bit_identical(one_a, three));
    omp_set_num_threads(omp_get_num_procs());
}

}  // namespace
}  // namespace sabo
