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

dem::DemSolver make_channel_solver(int threads) {
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
    return {scene.particles, scene.walls, dem.laws, scene.gravity, dem.dt, dem.skin};
}

std::vector<Vec3> run_channel(int threads, int steps, int reorder = 0) {
    dem::DemSolver s = make_channel_solver(threads);
    s.set_reorder_interval(reorder);
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
    // with the grains re-sorted by cell every third list build: the order depends on positions only
    const auto sorted_one = run_channel(1, steps, 3);
    const auto sorted_two = run_channel(2, steps, 3);
    EXPECT_TRUE(bit_identical(sorted_one, sorted_two));
    omp_set_num_threads(omp_get_num_procs());
}

// A reorder renumbers the grains and remaps every contact history, flipping the tangential spring
// and the rolling torque of pairs whose owner changed: the forces right after must be those of the
// same state without the reorder (to round-off from the summation order), grain by grain.
TEST(Reordering, RemapsContactHistoriesExactly) {
    dem::DemSolver plain = make_channel_solver(1);
    dem::DemSolver sorted = make_channel_solver(1);
    for (int k = 0; k < 5000; ++k) plain.step(), sorted.step();  // identical so far, sticking springs loaded
    sorted.set_reorder_interval(1);
    plain.set_wall_active(0, true);  // forces a list build at the next step in both
    sorted.set_wall_active(0, true);
    plain.step();
    sorted.step();
    const auto& ids = sorted.ids();
    const auto& fa = plain.forces();
    const auto& fb = sorted.forces();
    const auto& ta = plain.particles().t;
    const auto& tb = sorted.particles().t;
    std::size_t moved = 0;
    double f_max = 0.0, f_err = 0.0, t_max = 0.0, t_err = 0.0;
    for (std::size_t i = 0; i < plain.mobile_count(); ++i) {
        moved += ids[i] != i;
        f_max = std::max(f_max, norm(fa[ids[i]]));
        f_err = std::max(f_err, norm(fb[i] - fa[ids[i]]));
        t_max = std::max(t_max, norm(ta[ids[i]]));
        t_err = std::max(t_err, norm(tb[i] - ta[ids[i]]));
    }
    EXPECT_GT(moved, plain.mobile_count() / 4);  // the reorder did renumber
    EXPECT_GT(f_max, 1.0);
    EXPECT_LT(f_err, 1e-9 * f_max);
    EXPECT_LT(t_err, 1e-9 * t_max);
    omp_set_num_threads(omp_get_num_procs());
}

}  // namespace
}  // namespace sabo
