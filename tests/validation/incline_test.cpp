// SPDX-License-Identifier: MIT
// CASES §C6: a block (sphere whose rotation is locked by a huge μ_r) on an incline sticks below
// tan θ = μ_s and slides above with a = g (sin θ − μ_d cos θ); a sphere rolling with constant
// rolling resistance accelerates with a = 5/7 g (sin θ − μ_r cos θ), or stops when tan θ < μ_r.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dem/test_support.h"

namespace sabo {
namespace {

constexpr double g = 9.81, r = 0.05, rho = 2500.0, kn = 1e6;

// Sphere resting on the bed plane z = 0 of a channel tilted by θ (gravity in the channel frame),
// starting at its static overlap with velocity v0 along X, rolling without slip when `rolling`.
dem::DemSolver sphere_on_incline(double theta, const test::LawSpec& spec, double v0 = 0.0,
                                 bool rolling = false) {
    dem::Particles p;
    const double m = test::mass_of(r, rho);
    const double delta0 = m * g * std::cos(theta) / kn;
    p.add_mobile({0.5, 0.5, r - delta0}, r, rho, {v0, 0, 0});
    if (rolling) p.w[0] = {0, v0 / r, 0};
    std::vector<dem::Wall> walls{dem::Wall::plane("bed", {0, 0, 0}, {0, 0, 1})};
    const auto law = test::linear_law(spec);
    const double tc = law.normal.contact_time(m);
    return dem::DemSolver(p, walls, test::same_everywhere(law),
                          {g * std::sin(theta), 0, -g * std::cos(theta)}, tc / 40.0, 0.1 * r);
}

void run_until(dem::DemSolver& s, double t) {
    while (s.time() < t) s.step();
}

// Tilting table: the slope grows slowly from 0 (0.5 deg/s); the block must hold until tan θ = μ_s
// and break loose there. (Released suddenly on a slope, a critically damped tangential spring
// overshoots the static load by e^-2 = 13.5 %, so a sudden-release test cannot probe the threshold.)
TEST(BlockOnIncline, TiltingTableBreaksLooseAtTanThetaEqualMuS) {
    const double mu_s = 0.5, rate = 0.5 * 3.141592653589793 / 180.0;  // rad/s
    auto s = sphere_on_incline(0.0, {.kn = kn, .restitution = 0.2, .mu_s = mu_s, .mu_r = 1e6});
    double theta = 0.0, slip_theta = -1.0;
    const double x0 = s.particles().x[0].x;
    while (theta < std::atan(1.2 * mu_s)) {
        theta = rate * s.time();
        s.set_gravity({g * std::sin(theta), 0, -g * std::cos(theta)});
        s.step();
        if (slip_theta < 0.0 && s.particles().x[0].x - x0 > 1e-3) slip_theta = theta;
        if (slip_theta < 0.0 && std::tan(theta) < 0.99 * mu_s) {
            // still holding: displacement is the elastic deflection of the tangential spring only
            ASSERT_LT(s.particles().x[0].x - x0, 1.2 * mu_s * 1.309 * g / (2.0 / 7.0 * kn))
                << "theta " << theta;
        }
    }
    ASSERT_GT(slip_theta, 0.0);
    EXPECT_NEAR(std::tan(slip_theta), mu_s, 0.01 * mu_s);
}

TEST(BlockOnIncline, StaysAtRestBelowStaticFriction) {
    const double mu_s = 0.5;
    // sudden release at tan θ = 0.8 μ_s (below the 1/1.135 overshoot limit)
    auto s =
        sphere_on_incline(std::atan(0.8 * mu_s), {.kn = kn, .restitution = 0.2, .mu_s = mu_s, .mu_r = 1e6});
    run_until(s, 1.0);
    const double x1 = s.particles().x[0].x;
    run_until(s, 2.0);
    EXPECT_LT(std::abs(s.particles().x[0].x - x1), 1e-9);
    EXPECT_LT(norm(s.particles().v[0]), 1e-8);
}

TEST(BlockOnIncline, SlidesAboveStaticFrictionWithAnalyticAcceleration) {
    const double mu_s = 0.5, mu_d = 0.9 * mu_s;
    for (double ratio : {1.05, 1.5}) {
        const double theta = std::atan(ratio * mu_s);
        auto s = sphere_on_incline(theta, {.kn = kn, .restitution = 0.2, .mu_s = mu_s, .mu_r = 1e6});
        run_until(s, 0.2);
        const double v1 = s.particles().v[0].x, t1 = s.time();
        run_until(s, 1.2);
        const double a = (s.particles().v[0].x - v1) / (s.time() - t1);
        const double expected = g * (std::sin(theta) - mu_d * std::cos(theta));
        EXPECT_NEAR(a, expected, 0.01 * expected) << "tan θ / μ_s = " << ratio;
    }
}

constexpr dem::RollingModel rolling_models[] = {dem::RollingModel::constraint,
                                                dem::RollingModel::directional};

std::string name_of(dem::RollingModel model) {
    return model == dem::RollingModel::constraint ? "constraint" : "directional";
}

class SphereOnIncline : public testing::TestWithParam<dem::RollingModel> {};

TEST_P(SphereOnIncline, RollsWithConstantResistanceAboveThreshold) {
    const double mu_r = 0.1;
    for (double tan_theta : {0.2, 0.4}) {
        const double theta = std::atan(tan_theta);
        auto s = sphere_on_incline(
            theta, {.kn = kn, .restitution = 0.2, .mu_s = 1.0, .mu_r = mu_r, .rolling_model = GetParam()});
        run_until(s, 0.2);
        const double v1 = s.particles().v[0].x, t1 = s.time();
        run_until(s, 1.2);
        const double a = (s.particles().v[0].x - v1) / (s.time() - t1);
        const double expected = 5.0 / 7.0 * g * (std::sin(theta) - mu_r * std::cos(theta));
        EXPECT_NEAR(a, expected, 0.01 * expected) << "tan θ = " << tan_theta;
        // rolling, not sliding: the contact point is at rest
        EXPECT_NEAR(s.particles().v[0].x, r * s.particles().w[0].y, 1e-3 * s.particles().v[0].x);
    }
}

TEST_P(SphereOnIncline, StopsBelowRollingThresholdAndStaysAtRest) {
    const double mu_r = 0.1, tan_theta = 0.05, v0 = 1.0;
    const double theta = std::atan(tan_theta);
    auto s = sphere_on_incline(
        theta, {.kn = kn, .restitution = 0.2, .mu_s = 1.0, .mu_r = mu_r, .rolling_model = GetParam()}, v0,
        true);
    const double decel = 5.0 / 7.0 * g * (mu_r * std::cos(theta) - std::sin(theta));
    const double t_stop = v0 / decel;
    double stopped_at = -1.0;
    while (s.time() < 2.0 * t_stop) {
        s.step();
        if (stopped_at < 0.0 && s.particles().v[0].x <= 1e-4) stopped_at = s.time();
    }
    EXPECT_NEAR(stopped_at, t_stop, 0.01 * t_stop);
    const double x1 = s.particles().x[0].x;
    run_until(s, 3.0 * t_stop);
    EXPECT_LT(std::abs(s.particles().x[0].x - x1), 1e-6);
    if (GetParam() == dem::RollingModel::constraint) {
        EXPECT_LT(norm(s.particles().w[0]), 1e-6);
    } else {
        // the directional torque is found from each step's rotation after the friction torque's kick
        // (Δt r m g sin θ / J = Δt 5/2 g sin θ / r) and stops it; the synchronous ω reported, the mean of
        // the half steps' before and after it, stays within that kick of zero while the grain does not turn
        EXPECT_LT(norm(s.particles().w[0]), s.dt() * 2.5 * g * std::sin(theta) / r);
    }
}

INSTANTIATE_TEST_SUITE_P(RollingModels, SphereOnIncline, testing::ValuesIn(rolling_models),
                         [](const testing::TestParamInfo<dem::RollingModel>& info) {
                             return name_of(info.param);
                         });

// Contact history must survive neighbour-list rebuilds: a grain resting on a large fixed sphere at
// 20° from its top, rotation locked, must stay put even when the lists are rebuilt every step.
TEST(ContactHistory, SurvivesListRebuilds) {
    const double big = 0.5, beta = 20.0 * 3.141592653589793 / 180.0;
    for (bool rebuild_every_step : {false, true}) {
        dem::Particles p;
        const double m = test::mass_of(r, rho);
        const double delta0 = m * g * std::cos(beta) / kn;
        const double dist = big + r - delta0;
        p.add_mobile({dist * std::sin(beta), 0, dist * std::cos(beta)}, r, rho);
        p.add_fixed({0, 0, 0}, big);
        const auto law = test::linear_law({.kn = kn, .restitution = 0.2, .mu_s = 0.5, .mu_r = 1e6});
        dem::DemSolver s(p, {}, test::same_everywhere(law), {0, 0, -g}, law.normal.contact_time(m) / 40.0,
                         0.01);
        // settle: the tangential spring deflects elastically by m g sin β / k_t ≈ 1.6e-5 m
        for (int k = 0; k < 10000; ++k) s.step();
        const Vec3 x0 = s.particles().x[0];
        const auto builds0 = s.list_builds();
        for (int k = 0; k < 20000; ++k) {
            if (rebuild_every_step) s.invalidate_lists();
            s.step();
        }
        EXPECT_LT(norm(s.particles().x[0] - x0), 1e-9) << "rebuild every step: " << rebuild_every_step;
        if (rebuild_every_step) {
            EXPECT_GE(s.list_builds() - builds0, 20000u);
        }
    }
}

}  // namespace
}  // namespace sabo

namespace sabo {
namespace {

// An undamped tangential spring must neither gain nor lose energy: a rotation-locked block resting
// on a plane (gravity along −Z only), pushed sideways, oscillates on its tangential spring without
// slipping (μ_s = 10, α_t = 0). With the spring advanced after the trial force (one-step lag) the
// amplitude would grow by ~(ω_t Δt)²/2 per step: e^50 over this run.
TEST(TangentialSpring, UndampedOscillationKeepsItsAmplitude) {
    dem::Particles p;
    const double m = test::mass_of(r, rho);
    p.add_mobile({0.5, 0.5, r - m * g / kn}, r, rho, {0.01, 0, 0});
    std::vector<dem::Wall> walls{dem::Wall::plane("bed", {0, 0, 0}, {0, 0, 1})};
    const auto law =
        test::linear_law({.kn = kn, .restitution = 0.2, .mu_s = 10.0, .alpha_t = 0.0, .mu_r = 1e6});
    const double tc = law.normal.contact_time(m);
    dem::DemSolver s(p, walls, test::same_everywhere(law), {0, 0, -g}, tc / 20.0, 0.1 * r);
    const double period = 2.0 * 3.141592653589793 / std::sqrt(law.normal.kt_ratio * kn / m);
    const int steps = static_cast<int>(100 * period / s.dt());
    double early_peak = 0.0, late_peak = 0.0;
    for (int k = 0; k < steps; ++k) {
        s.step();
        const double vx = std::abs(s.particles().v[0].x);
        if (k < static_cast<int>(2 * period / s.dt())) early_peak = std::max(early_peak, vx);
        if (k > steps - static_cast<int>(2 * period / s.dt())) late_peak = std::max(late_peak, vx);
    }
    EXPECT_GT(early_peak, 0.0095);
    EXPECT_NEAR(late_peak, early_peak, 0.02 * early_peak) << "over 100 tangential periods";
}

}  // namespace
}  // namespace sabo
