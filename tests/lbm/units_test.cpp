// SPDX-License-Identifier: MIT
// The SI ↔ lattice converter and the set-up checks of SPEC §2.5.
#include "lbm/units.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sabo::lbm {
namespace {

// CASES C5: Δx = 2.5 cm, Δt = 5e-4 s, ρ = 1500 kg/m³, η = 20 Pa·s ⇒ τ ≈ 0.532 (SPEC §2.1's check).
LatticeRequest c5() {
    LatticeRequest r;
    r.dx_m = 0.025;
    r.dt_s = 5e-4;
    r.density_kg_m3 = 1500.0;
    r.viscosity_Pa_s = 20.0;
    r.velocity_scale_m_s = 8.0;
    r.where = "c5.toml";
    return r;
}

TEST(LatticeUnits, CaseC5GivesTheSpecTau) {
    const auto n = check_lattice(c5());
    EXPECT_NEAR(n.nu_lb, 20.0 / 1500.0 * 5e-4 / (0.025 * 0.025), 1e-15);
    EXPECT_NEAR(n.tau, 0.532, 5e-4);
    EXPECT_NEAR(n.u_lb, 8.0 * 5e-4 / 0.025, 1e-15);
    EXPECT_NEAR(n.mach, 0.16 * std::sqrt(3.0), 1e-12);
    EXPECT_TRUE(n.warnings.empty());
}

TEST(LatticeUnits, ConversionsRoundTrip) {
    const UnitConverter u(0.025, 5e-4, 1500.0);
    EXPECT_NEAR(u.velocity_si(u.velocity(3.7)), 3.7, 1e-14);
    EXPECT_NEAR(u.stress_si(u.stress(500.0)), 500.0, 1e-10);
    EXPECT_NEAR(u.strain_rate_si(u.strain_rate(12.0)), 12.0, 1e-12);
    // a lattice force of 1 is ρ Δx⁴/Δt² (mass ρΔx³ times acceleration Δx/Δt²)
    EXPECT_NEAR(u.force_si(1.0), 1500.0 * std::pow(0.025, 4) / (5e-4 * 5e-4), 1e-9);
    EXPECT_NEAR(u.mass_si(1.0), 1500.0 * std::pow(0.025, 3), 1e-15);
    // gravity: a_LB = g Δt²/Δx
    EXPECT_NEAR(u.acceleration(9.81), 9.81 * 2.5e-7 / 0.025, 1e-18);
    EXPECT_THROW(UnitConverter(0.0, 1e-3, 1000.0), InputError);
}

// Δρ/ρ = 3 g H Δt²/Δx² over the fluid's depth: C5's 1.35 m at Δx 2.5 cm, Δt 5e-4 s is 1.6 % (warned); a
// fluid 4 m deep at 1.6 times the step, 12 % (refused, with the step that would do); 1 cm deep, quiet.
TEST(LatticeUnits, WarnsAndRefusesHydrostaticCompression) {
    auto r = c5();
    r.gravity_m_s2 = 9.81;
    r.depth_m = 1.35;
    const LatticeNumbers n = check_lattice(r);
    EXPECT_NEAR(n.hydrostatic_variation, 3.0 * 9.81 * 1.35 * 0.02 * 0.02, 1e-12);
    EXPECT_TRUE(std::any_of(n.warnings.begin(), n.warnings.end(), [](const std::string& w) {
        return w.find("over its depth") != std::string::npos;
    }));
    r.depth_m = 0.01;
    EXPECT_NEAR(check_lattice(r).hydrostatic_variation, 3.0 * 9.81 * 0.01 * 0.02 * 0.02, 1e-15);
    EXPECT_TRUE(std::none_of(check_lattice(r).warnings.begin(), check_lattice(r).warnings.end(),
                             [](const std::string& w) { return w.find("depth") != std::string::npos; }));
    r.depth_m = 4.0;
    r.dt_s = 8e-4;  // 3 g H (Δt/Δx)² = 117.7 x 1.024e-3 = 0.12
    r.velocity_scale_m_s = 1.0;
    try {
        (void)check_lattice(r);
        FAIL() << "a 12 % density variation was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("over its 4 m depth"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("reduce dt"), std::string::npos) << e.what();
    }
}

TEST(LatticeUnits, RefusesUnstableAndOversizeSetUps) {
    auto r = c5();
    r.dt_s = 0.05;  // τ far above τ_max
    EXPECT_THROW(
        {
            try {
                (void)check_lattice(r);
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("c5.toml"), std::string::npos);
                EXPECT_NE(std::string(e.what()).find("tau_max"), std::string::npos);
                throw;
            }
        },
        InputError);
    r = c5();
    r.velocity_scale_m_s = 60.0;  // Mach 2
    EXPECT_THROW((void)check_lattice(r), InputError);
    r.velocity_scale_m_s = 20.0;  // Mach 0.69: warned
    EXPECT_EQ(check_lattice(r).warnings.size(), 1u);
    // the scale is the case's estimate: the warning says which, and which key states a slower flow
    EXPECT_EQ(check_lattice(r).warnings[0].find("debris.velocity_scale_m_s"), std::string::npos);
    r.velocity_key = "debris.velocity_scale_m_s";
    const std::string warned = check_lattice(r).warnings.at(0);
    EXPECT_NE(warned.find("velocity scale 20 m/s"), std::string::npos) << warned;
    EXPECT_NE(warned.find("set debris.velocity_scale_m_s"), std::string::npos) << warned;
    r = c5();
    r.grain_d_mean_m = 0.08;  // Δx > d/4
    EXPECT_THROW((void)check_lattice(r), InputError);
    r.grain_d_mean_m = 0.1;
    r.grain_d_min_m = 0.1;  // Δx > d_min/10: warned
    EXPECT_EQ(check_lattice(r).warnings.size(), 1u);
    r = c5();
    r.nodes = 4'000'000;
    r.bytes_per_node = 100;
    r.memory_limit_bytes = 100'000'000;
    EXPECT_THROW((void)check_lattice(r), InputError);
}

}  // namespace
}  // namespace sabo::lbm
