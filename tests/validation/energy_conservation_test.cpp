// SPDX-License-Identifier: MIT
// CASES §C6: energy conservation with no damping. A dilute gas of elastic, frictionless spheres in
// a closed box; kinetic energy compared whenever no contact is active. Velocity Verlet conserves a
// shadow energy: the error of one collision is O((ω Δt)²) with ω = π / t_c, so it must shrink about
// 4× when Δt is halved.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dem/test_support.h"

namespace sabo {
namespace {

double energy_drift(int steps_per_contact, std::uint64_t* collisions_out) {
    const double r = 0.05, rho = 2500.0, box = 1.0;
    dem::Particles p;
    std::mt19937_64 rng(7);
    auto u = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k)
                p.add_mobile({0.125 + 0.25 * i, 0.125 + 0.25 * j, 0.125 + 0.25 * k}, r, rho,
                             {2 * u() - 1, 2 * u() - 1, 2 * u() - 1});
    std::vector<dem::Wall> walls{
        dem::Wall::plane("x0", {0, 0, 0}, {1, 0, 0}), dem::Wall::plane("x1", {box, 0, 0}, {-1, 0, 0}),
        dem::Wall::plane("y0", {0, 0, 0}, {0, 1, 0}), dem::Wall::plane("y1", {0, box, 0}, {0, -1, 0}),
        dem::Wall::plane("z0", {0, 0, 0}, {0, 0, 1}), dem::Wall::plane("z1", {0, 0, box}, {0, 0, -1})};
    const auto law =
        test::linear_law({.kn = 1e6, .restitution = 1.0, .clip = true, .mu_s = 0.0, .alpha_t = 0.0});
    const double tc = law.normal.contact_time(0.5 * test::mass_of(r, rho));
    dem::DemSolver s(p, walls, test::same_everywhere(law), {0, 0, 0}, tc / steps_per_contact, 0.01);
    const auto e0 = s.kinetic_energy().translational;
    double worst = 0.0;
    std::uint64_t collisions = 0, prev_contacts = 0;
    while (s.time() < 2.0) {
        s.step();
        if (s.stats().contacts > prev_contacts) collisions += s.stats().contacts - prev_contacts;
        prev_contacts = s.stats().contacts;
        if (s.stats().contacts == 0)
            worst = std::max(worst, std::abs(s.kinetic_energy().translational / e0 - 1.0));
    }
    *collisions_out = collisions;
    return worst;
}

TEST(EnergyConservation, ElasticFrictionlessGasConservesKineticEnergy) {
    std::uint64_t n20 = 0, n40 = 0;
    const double drift20 = energy_drift(20, &n20);
    const double drift40 = energy_drift(40, &n40);
    ASSERT_GT(n20, 100u) << "the test needs many collisions";
    // (π/20)² ≈ 2.5e-2 per collision worst case; errors of separate collisions partly cancel.
    EXPECT_LT(drift20, 5e-3) << n20 << " collisions";
    EXPECT_LT(drift40, 0.4 * drift20) << "second order: halving dt must cut the drift ~4x";
}

}  // namespace
}  // namespace sabo

namespace sabo {
namespace {

// With elastic springs and no dissipation, kinetic + stored elastic energy of one collision is
// conserved at every step, not only between collisions (checks elastic_energy()).
TEST(EnergyConservation, KineticPlusElasticEnergyIsConstantDuringContact) {
    const double r = 0.05, rho = 2500.0;
    dem::Particles p;
    p.add_mobile({0, 0, 0}, r, rho, {0.5, 0, 0});
    p.add_mobile({2 * r + 1e-6, 0, 0}, r, rho, {-0.5, 0, 0});
    const auto law =
        test::linear_law({.kn = 1e6, .restitution = 1.0, .clip = true, .mu_s = 0.0, .alpha_t = 0.0});
    const double tc = law.normal.contact_time(0.5 * test::mass_of(r, rho));
    dem::DemSolver s(p, {}, test::same_everywhere(law), {0, 0, 0}, tc / 200.0, 0.01);
    const double e0 = s.kinetic_energy().translational;
    double worst = 0.0, peak_elastic = 0.0;
    for (int k = 0; k < 400; ++k) {
        s.step();
        peak_elastic = std::max(peak_elastic, s.elastic_energy());
        worst = std::max(worst, std::abs((s.kinetic_energy().translational + s.elastic_energy()) / e0 - 1.0));
    }
    EXPECT_GT(peak_elastic, 0.9 * e0) << "the springs must store nearly all the energy at maximum overlap";
    // Verlet: kinetic energy is taken at whole steps with half-step-lagged velocities: O((ω Δt)²)
    EXPECT_LT(worst, 1e-3);
}

}  // namespace
}  // namespace sabo
