// SPDX-License-Identifier: MIT
// CASES §C6: binary head-on collision — restitution and contact duration against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/config.h"
#include "dem/dem_setup.h"
#include "dem/test_support.h"

namespace sabo {
namespace {

struct Collision {
    double restitution;   // −(v1' − v2')/(v1 − v2)
    double contact_time;  // s, steps with an active contact × Δt
};

template <class Normal>
Collision collide(const dem::ContactLaw<Normal>& law, double r, double rho, double speed, double dt) {
    dem::Particles p;
    p.add_mobile({0, 0, 0}, r, rho, {0.5 * speed, 0, 0});
    p.add_mobile({2 * r + 1e-6, 0, 0}, r, rho, {-0.5 * speed, 0, 0});
    dem::DemSolver s(p, {}, dem::ContactLawSet<Normal>{law, law, law}, {0, 0, 0}, dt, 0.1 * r);
    std::uint64_t in_contact = 0;
    bool touched = false;
    for (int k = 0; k < 1'000'000; ++k) {
        s.step();
        if (s.stats().contacts > 0) {
            ++in_contact;
            touched = true;
        } else if (touched) {
            break;
        }
    }
    const auto& v = s.particles().v;
    return {-(v[0].x - v[1].x) / speed, static_cast<double>(in_contact) * dt};
}

constexpr double r = 0.05, rho = 2500.0;

TEST(BinaryCollision, LinearClippedRestitutionMatchesSchwagerPoeschelAtSeveralSpeeds) {
    const auto law = test::linear_law({.kn = 1e6, .restitution = 0.2, .clip = true, .mu_s = 0.0});
    const double m_eff = 0.5 * test::mass_of(r, rho);
    const double tc = law.normal.contact_time(m_eff);
    const double expected = dem::clipped_linear_restitution(law.normal.alpha_n);  // 0.3249
    // The contact switches on and off inside a step, so e converges to the closed form at first
    // order in Δt (docs/dem.md lists e against t_c/Δt); t_c/200 resolves it well within 1 %.
    for (double v : {0.05, 0.5, 2.0, 6.0}) {
        const auto c = collide(law, r, rho, v, tc / 200.0);
        EXPECT_NEAR(c.restitution, expected, 0.01 * expected) << "impact speed " << v;
    }
}

TEST(BinaryCollision, LinearUnclippedRestitutionAndContactTimeAreExact) {
    for (double zeta : {0.2, 0.5, 0.9}) {
        const auto law = test::linear_law({.kn = 1e6, .restitution = zeta, .clip = false, .mu_s = 0.0});
        const double m_eff = 0.5 * test::mass_of(r, rho);
        const double tc = law.normal.contact_time(m_eff);  // π / sqrt(k/m̃ (1 − α²))
        for (double v : {0.1, 3.0}) {
            const auto c = collide(law, r, rho, v, tc / 1000.0);
            EXPECT_NEAR(c.restitution, zeta, 0.01 * zeta) << "zeta " << zeta << " v " << v;
            EXPECT_NEAR(c.contact_time, tc, 0.02 * tc) << "zeta " << zeta << " v " << v;
        }
    }
}

dem::ContactLaw<dem::HertzNormal> hertz_law(double zeta, bool clip) {
    dem::ContactLaw<dem::HertzNormal> law;
    const double e = 5e7, nu = 0.25;
    law.normal.e_star = e / (2.0 * (1.0 - nu * nu));
    law.normal.g_star = e / (4.0 * (2.0 - nu) * (1.0 + nu));
    law.normal.beta = zeta >= 1.0 ? 0.0 : dem::damping_ratio_from_restitution(zeta);
    law.normal.clip_attractive = clip;
    law.tangential = {1.0, 0.0, 0.0, dem::FrictionMemory::hysteresis};
    return law;
}

TEST(BinaryCollision, HertzElasticContactTimeMatchesHertzTheory) {
    const auto law = hertz_law(1.0, true);
    const double m_eff = 0.5 * test::mass_of(r, rho), r_eff = 0.5 * r;
    for (double v : {0.1, 1.0, 5.0}) {
        // t_c = 2.868 (m̃² / (r̃ E*² v))^{1/5}; also SPEC's 2.214 (ρ/E*)^{2/5} d / v^{1/5}
        const double tc = law.normal.contact_time(m_eff, r_eff, v);
        EXPECT_NEAR(tc, 2.214 * std::pow(rho / law.normal.e_star, 0.4) * 2 * r / std::pow(v, 0.2), 1e-3 * tc);
        const auto c = collide(law, r, rho, v, tc / 200.0);
        EXPECT_NEAR(c.contact_time, tc, 0.02 * tc) << "v " << v;
        EXPECT_NEAR(c.restitution, 1.0, 0.01) << "v " << v;
    }
}

TEST(BinaryCollision, HertzDampedRestitutionIsSpeedIndependentAndMatchesReference) {
    for (bool clip : {true, false}) {
        const auto law = hertz_law(0.5, clip);
        const double m_eff = 0.5 * test::mass_of(r, rho), r_eff = 0.5 * r;
        // reference: 1D RK4 integration of m̃ δ'' = −F_n(δ, δ') with 20000 steps per contact
        const double tc1 = law.normal.contact_time(m_eff, r_eff, 1.0);
        const double reference = dem::effective_restitution(law.normal, m_eff, r_eff, 1.0, tc1);
        for (double v : {0.1, 1.0, 5.0}) {
            const double tc = law.normal.contact_time(m_eff, r_eff, v);
            const auto c = collide(law, r, rho, v, tc / 200.0);
            EXPECT_NEAR(c.restitution, reference, 0.01 * reference) << "clip " << clip << " v " << v;
        }
    }
}

// contact.restitution_meaning = "achieved": the dashpot is calibrated so that two grains really rebound with
// ζ although the attractive force is clipped (ζ = 0.2: α_n 0.456 → 0.72), at any speed.
TEST(BinaryCollision, AchievedRestitutionIsTheReboundOfTheClippedContact) {
    const auto cfg = Config::from_string(
        "[contact]\nkn_N_m = 1e6\nrestitution = 0.2\nrestitution_meaning = \"achieved\"\n"
        "[contact.particle_particle]\nmu_s = 0.0\nmu_r = 0.0\n",
        "achieved.toml");
    const auto settings = dem::read_dem_settings(cfg, {r, r, rho, 2.0});
    const auto& law = std::get<dem::ContactLawSet<dem::LinearNormal>>(settings.laws).particle_particle;
    EXPECT_GT(law.normal.alpha_n, 1.0 / std::numbers::sqrt2);  // beyond what ζ = 0.2 sets without clipping
    EXPECT_NEAR(settings.effective_restitution, 0.2, 1e-4);
    const double tc = law.normal.contact_time(0.5 * test::mass_of(r, rho));
    for (double v : {0.5, 4.0})
        EXPECT_NEAR(collide(law, r, rho, v, tc / 200.0).restitution, 0.2, 0.01 * 0.2) << v;
}

}  // namespace
}  // namespace sabo
