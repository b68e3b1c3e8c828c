// SPDX-License-Identifier: MIT
#include "dem/dem_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.h"
#include "dem/friction_calibration.h"

namespace sabo::dem {
namespace {

const GrainScale grains{0.0475, 0.0525, 2500.0, 5.0};

Config config(const std::string& contact) {
    return Config::from_string("[contact]\nrestitution = 0.2\n" + contact, "setup.toml");
}

TEST(DemSetup, LinearTimeStepFromTheSmallestGrainPair) {
    const auto cfg = config("kn_N_m = 1e6\n[contact.particle_particle]\nfriction_angle_deg = 30.0\n");
    const auto s = read_dem_settings(cfg, grains);
    const double m_min = 2500.0 * 4.0 / 3.0 * std::numbers::pi * std::pow(0.0475, 3);
    const double alpha = damping_ratio_from_restitution(0.2);
    const double tc = std::numbers::pi / std::sqrt(1e6 / (0.5 * m_min) * (1 - alpha * alpha));
    EXPECT_NEAR(s.contact_time, tc, 1e-12 * tc);
    EXPECT_NEAR(s.dt, tc / 20.0, 1e-15);
    EXPECT_NEAR(s.effective_restitution, clipped_linear_restitution(alpha), 1e-4);
    const auto& laws = std::get<ContactLawSet<LinearNormal>>(s.laws);
    const auto f = friction_from_repose_angle(30.0);
    EXPECT_DOUBLE_EQ(laws.particle_particle.rolling.mu_r, f.mu_r);
    EXPECT_DOUBLE_EQ(laws.particle_wall.rolling.mu_r, 2.0 * f.mu_r);  // default wall mapping
    EXPECT_DOUBLE_EQ(laws.particle_barrier.tangential.mu_s, f.mu_s);
    EXPECT_DOUBLE_EQ(laws.particle_particle.tangential.mu_d, 0.9 * f.mu_s);
}

TEST(DemSetup, HertzContactTimeAndModuli) {
    const auto cfg = config(
        "normal_model = \"hertz\"\nyoungs_modulus_Pa = 5e7\npoisson_ratio = 0.25\n"
        "[contact.particle_particle]\nmu_s = 0.5\nmu_r = 0.05\n");
    const auto s = read_dem_settings(cfg, grains);
    const auto& laws = std::get<ContactLawSet<HertzNormal>>(s.laws);
    EXPECT_NEAR(laws.particle_particle.normal.e_star, 5e7 / (2 * (1 - 0.0625)), 1e-6);  // identical grains
    EXPECT_NEAR(laws.particle_wall.normal.e_star, 5e7 / (1 - 0.0625), 1e-6);            // rigid wall
    // grain–grain, SPEC: t_c ≈ 2.214 (ρ/E*)^{2/5} d_min / v^{1/5} with v = 2 v_max = 10 m/s
    const double t_pp =
        2.214 * std::pow(2500.0 / laws.particle_particle.normal.e_star, 0.4) * 0.095 / std::pow(10.0, 0.2);
    // grain on a rigid wall: m̃ = m, r̃ = r, E* twice the grain–grain value — shorter by (1/2)^{1/5}
    const double m_min = 2500.0 * 4.0 / 3.0 * std::numbers::pi * std::pow(0.0475, 3);
    const double e_w = laws.particle_wall.normal.e_star;
    const double t_wall = 2.8683 * std::pow(m_min * m_min / (0.0475 * e_w * e_w * 10.0), 0.2);
    EXPECT_NEAR(t_wall / t_pp, std::pow(0.5, 0.2), 2e-3);
    EXPECT_NEAR(s.contact_time, std::min(t_pp, t_wall), 2e-3 * t_wall);  // the shortest class sets Δt
}

TEST(DemSetup, RefusesLargeTimeStepsAndContradictoryFriction) {
    EXPECT_THROW((void)read_dem_settings(
                     Config::from_string(
                         "[contact]\nrestitution = 0.2\nkn_N_m = 1e6\n"
                         "[contact.particle_particle]\nfriction_angle_deg = 30.0\n[dem]\ndt_s = 1e-3\n",
                         "a.toml"),
                     grains),
                 InputError);
    EXPECT_THROW((void)read_dem_settings(config("kn_N_m = 1e6\n[contact.particle_particle]\n"
                                                "friction_angle_deg = 30.0\nmu_s = 0.5\n"),
                                         grains),
                 InputError);
    EXPECT_THROW((void)read_dem_settings(config("kn_N_m = 1e6\n[contact.particle_particle]\n"
                                                "friction_angle_deg = 40.0\n"),
                                         grains),
                 InputError);  // outside the calibration law
}

// restitution_meaning = "achieved" calibrates the damping of either normal law so that the clipped impact
// rebounds with ζ; a ζ below what the most damped contact reaches is refused, naming the key.
TEST(DemSetup, AchievedRestitutionCalibratesTheDampingOfBothLaws) {
    const std::string friction = "[contact.particle_particle]\nfriction_angle_deg = 30.0\n";
    const auto linear =
        read_dem_settings(config("kn_N_m = 1e6\nrestitution_meaning = \"achieved\"\n" + friction), grains);
    EXPECT_NEAR(linear.effective_restitution, 0.2, 1e-4);
    // the time step stays that of the dashpot form (a longer one made resting grains spin up)
    const auto dashpot = read_dem_settings(config("kn_N_m = 1e6\n" + friction), grains);
    EXPECT_EQ(linear.dt, dashpot.dt);
    const auto hertz = read_dem_settings(config("normal_model = \"hertz\"\nyoungs_modulus_Pa = 5e7\n"
                                                "poisson_ratio = 0.25\nrestitution_meaning = \"achieved\"\n" +
                                                friction),
                                         grains);
    EXPECT_NEAR(hertz.effective_restitution, 0.2, 1e-4);
    try {
        (void)read_dem_settings(Config::from_string("[contact]\nrestitution = 0.1\nkn_N_m = 1e6\n"
                                                    "restitution_meaning = \"achieved\"\n" +
                                                        friction,
                                                    "low.toml"),
                                grains);
        ADD_FAILURE() << "an unreachable restitution was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("contact.restitution"), std::string::npos) << e.what();
    }
}

TEST(DemSetup, RollingModelIsConstraintUnlessChosenAndAppliesToEveryClass) {
    const std::string contact = "kn_N_m = 1e6\n[contact.particle_particle]\nfriction_angle_deg = 30.0\n";
    const auto model_of = [](const DemSettings& s) {
        const auto& laws = std::get<ContactLawSet<LinearNormal>>(s.laws);
        EXPECT_EQ(laws.particle_wall.rolling.model, laws.particle_particle.rolling.model);
        EXPECT_EQ(laws.particle_barrier.rolling.model, laws.particle_particle.rolling.model);
        return laws.particle_particle.rolling.model;
    };
    EXPECT_EQ(model_of(read_dem_settings(config(contact), grains)), RollingModel::constraint);
    const auto directional =
        read_dem_settings(config(contact + "[dem]\nrolling_model = \"directional\"\n"), grains);
    EXPECT_EQ(model_of(directional), RollingModel::directional);
    EXPECT_NE(describe_contact(directional).find("directional rolling resistance"), std::string::npos);
    // extra sweeps iterate the constraint torque: refused with the directional model, naming the key
    try {
        (void)read_dem_settings(
            config(contact + "[dem]\nrolling_model = \"directional\"\nrolling_sweeps = 2\n"), grains);
        ADD_FAILURE() << "rolling_sweeps = 2 with the directional model was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("dem.rolling_sweeps"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)read_dem_settings(config(contact + "[dem]\nrolling_model = \"spring\"\n"), grains),
                 InputError);
}

TEST(DemSetup, PerGrainSkinsBetweenTheSkinAndTheLargestSkin) {
    const std::string contact = "kn_N_m = 1e6\n[contact.particle_particle]\nfriction_angle_deg = 30.0\n";
    const double d_max = 2.0 * grains.r_max;
    const auto defaults = read_dem_settings(config(contact), grains);
    EXPECT_DOUBLE_EQ(defaults.skin, 0.1 * d_max);
    EXPECT_DOUBLE_EQ(defaults.skin_max, default_skin_max_over_d * d_max);
    // a skin above the default largest skin raises the largest skin with it (one skin for all)
    const auto wide = read_dem_settings(config(contact + "[dem]\nskin_over_d = 0.8\n"), grains);
    EXPECT_DOUBLE_EQ(wide.skin_max, wide.skin);
    try {
        (void)read_dem_settings(config(contact + "[dem]\nskin_over_d = 0.2\nskin_max_over_d = 0.1\n"),
                                grains);
        ADD_FAILURE() << "a largest skin below the skin was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("dem.skin_max_over_d"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sabo::dem
