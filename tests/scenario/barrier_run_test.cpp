// SPDX-License-Identifier: MIT
// Scaled-down channel runs asserting physics that must hold (issue 3): a closed barrier retains
// everything, an outlet much wider than the grains lets most of the mass pass, and the forces the
// barrier and the walls receive account exactly for the grains' momentum change.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/flow_measures.h"
#include "analysis/force_balance.h"
#include "dem/dem_setup.h"
#include "dem/dem_solver.h"
#include "scenario/channel_case.h"

namespace sabo::scenario {
namespace {

// ~290 grains in a 1.0 m long block whose front is 0.8 m upstream of the barrier face (X = 5.5).
Config small_case(const std::string& barrier) {
    return Config::from_string(R"(
[case]
end_time_s = 2.0
[channel]
slope_deg = 35.0
[release]
length_m = 1.0
solid_volume_m3 = 0.15
[barrier]
face_x_m = 5.5
)" + barrier + R"(
[contact]
kn_N_m = 1.0e6
kt_over_kn = 0.2857142857142857
restitution = 0.2
[contact.particle_particle]
friction_angle_deg = 30.0
[contact.particle_wall]
friction_angle_deg = 30.0
[contact.particle_barrier]
friction_angle_deg = 30.0
)",
                               "small.toml");
}

struct SmallRun {
    ChannelCase scene;
    dem::DemSettings dem;
    std::unique_ptr<dem::DemSolver> solver;
};

SmallRun start(const Config& cfg) {
    SmallRun r;
    r.scene = build_channel_case(cfg);
    const auto& rel = r.scene.release;
    r.dem = dem::read_dem_settings(cfg, {rel.r_min, rel.r_max, rel.density, r.scene.velocity_scale});
    r.solver = std::make_unique<dem::DemSolver>(r.scene.particles, r.scene.walls, r.dem.laws, r.scene.gravity,
                                                r.dem.dt, r.dem.skin);
    return r;
}

void run_for(SmallRun& r, double seconds) {
    const auto steps = static_cast<std::uint64_t>(std::ceil(seconds / r.dem.dt));
    for (std::uint64_t s = 0; s < steps; ++s) r.solver->step();
}

TEST(BarrierRun, ClosedBarrierRetainsEverything) {
    SmallRun r = start(small_case("type = \"closed\"\n"));
    run_for(r, 2.0);
    const auto& p = r.solver->particles();
    EXPECT_EQ(analysis::non_retained_fraction(p, r.scene.barrier), 0.0);
    double x_max = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) x_max = std::max(x_max, p.x[i].x + p.r[i]);
    EXPECT_LT(x_max, 5.5 + 0.01);  // no grain beyond the face (overlap < 1 cm)
    EXPECT_GT(x_max, 5.3);         // and the mass did reach the barrier
}

TEST(BarrierRun, WideOutletLetsMostOfTheMassPass) {
    SmallRun r = start(small_case("type = \"slit\"\noutlet_width_m = 1.6\n"));  // S = 16 r
    run_for(r, 2.0);
    EXPECT_GT(analysis::non_retained_fraction(r.solver->particles(), r.scene.barrier), 0.5);
}

TEST(BarrierRun, WallAndBarrierForcesAccountForTheMomentumChange) {
    SmallRun r = start(small_case("type = \"closed\"\nmodel = \"spheres\"\n"));
    dem::DemSolver& s = *r.solver;
    const auto& p0 = s.particles();
    double mass = 0.0;
    Vec3 p_start{};
    for (std::size_t i = 0; i < p0.n_mobile; ++i) mass += p0.m[i], p_start += p0.m[i] * p0.v[i];
    // force the grains receive from walls and barrier = −(what those receive); trapezoidal impulse
    // matches velocity Verlet's momentum update exactly
    auto received = [&] {
        Vec3 f{};
        for (const auto& w : s.wall_forces()) f += w;
        for (std::size_t i = s.mobile_count(); i < s.forces().size(); ++i) f += s.forces()[i];
        return f;
    };
    auto barrier_received = [&] {
        Vec3 f{};
        for (std::size_t i = s.mobile_count(); i < s.forces().size(); ++i) f += s.forces()[i];
        return f;
    };
    Vec3 impulse{}, barrier_impulse{};
    Vec3 f_prev = received(), fb_prev = barrier_received();
    const auto steps = static_cast<std::uint64_t>(std::ceil(1.6 / r.dem.dt));
    for (std::uint64_t k = 0; k < steps; ++k) {
        s.step();
        const Vec3 f = received(), fb = barrier_received();
        impulse += 0.5 * r.dem.dt * (f_prev + f);
        barrier_impulse += 0.5 * r.dem.dt * (fb_prev + fb);
        f_prev = f, fb_prev = fb;
    }
    const auto& p = s.particles();
    Vec3 p_end{};
    for (std::size_t i = 0; i < p.n_mobile; ++i) p_end += p.m[i] * p.v[i];
    const Vec3 expected = p_start + (mass * s.time()) * r.scene.gravity - impulse;
    const double scale = mass * norm(r.scene.gravity) * s.time();
    EXPECT_LT(norm(p_end - expected), 1e-9 * scale) << "momentum balance";
    EXPECT_GT(barrier_impulse.x, 0.05 * scale) << "the barrier took part";
}

// Once the deposit is at rest its down-slope weight is carried by the barrier and the walls, split by
// analysis::wall_loads into bed, side walls and the others without loss.
TEST(BarrierRun, AtRestTheBarrierAndTheWallsCarryTheDownSlopeWeight) {
    SmallRun r = start(small_case("type = \"closed\"\nmodel = \"spheres\"\n"));
    dem::DemSolver& s = *r.solver;
    run_for(r, 4.0);
    const auto& p = s.particles();
    double mass = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) mass += p.m[i];
    const double weight_x = mass * r.scene.gravity.x;
    const auto ke = s.kinetic_energy();
    ASSERT_LT(ke.translational + ke.rotational, 1e-6 * mass * norm(r.scene.gravity) * 0.05) << "not at rest";
    Vec3 barrier{}, walls{};
    for (std::size_t i = s.mobile_count(); i < s.forces().size(); ++i) barrier += s.forces()[i];
    for (const auto& w : s.wall_forces()) walls += w;
    const analysis::WallLoads loads = analysis::wall_loads(s.walls(), s.wall_forces());
    EXPECT_NEAR(loads.bed_x + loads.side_walls_x + loads.other_x, walls.x, 1e-9 * weight_x);
    EXPECT_NEAR(barrier.x + walls.x, weight_x, 1e-3 * weight_x) << "force balance along the slope";
    EXPECT_GT(barrier.x, 0.5 * weight_x) << "the barrier holds most of it";
    EXPECT_LT(std::abs(loads.other_x), 1e-6 * weight_x) << "the deposit touches no end wall or ceiling";
}

TEST(SectionalBarrier, ConfigurationCHasSixPilesAndClearOutlets) {
    const auto cfg = small_case("type = \"sectional\"\nconfiguration = \"C\"\n");
    const auto c = build_channel_case(cfg);
    ASSERT_EQ(c.barrier.piles.size(), 6u);
    ASSERT_EQ(c.barrier.outlets.size(), 5u);
    for (const auto& o : c.barrier.outlets) EXPECT_NEAR(o.width(), 0.30, 1e-9);
    const auto& p = c.particles;
    for (std::size_t i = p.n_mobile; i < p.size(); ++i) {
        for (const auto& o : c.barrier.outlets) {
            EXPECT_TRUE(p.x[i].y + p.r[i] <= o.lo + 1e-9 || p.x[i].y - p.r[i] >= o.hi - 1e-9) << p.x[i].y;
        }
    }
    // every element belongs to a pile whose span contains it
    for (const auto& e : c.barrier.elements) {
        const auto& span = c.barrier.piles[static_cast<std::size_t>(e.pile)];
        EXPECT_GE(e.centre.y, span.lo - 1e-9);
        EXPECT_LE(e.centre.y, span.hi + 1e-9);
    }
    const auto boxes =
        build_channel_case(small_case("type = \"sectional\"\nconfiguration = \"L\"\nmodel = \"boxes\"\n"));
    EXPECT_EQ(boxes.barrier.wall_count, 3u);
    EXPECT_EQ(boxes.barrier.elements.size(), 3u);
}

}  // namespace
}  // namespace sabo::scenario
