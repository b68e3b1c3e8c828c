// SPDX-License-Identifier: MIT
// CASES §C6: a settled pile stays at rest. 216 grains with the full C2 contact model are poured
// into a small box; once settled the kinetic energy must be essentially zero (the rolling-torque
// cap and the friction spring stop every motion) and must stay so: no creep.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dem/friction_calibration.h"
#include "dem/test_support.h"

namespace sabo {
namespace {

// With the default single rolling sweep per step (warm-started torques, docs/dem.md) the pile is
// exactly at rest: measured kinetic energy ~3e-28 J and no displacement at all between 4 s and 6 s.
TEST(SettledPile, KineticEnergyDecaysToZeroAndThePileDoesNotCreep) {
    const double r = 0.05, rho = 2500.0, box = 0.7, g = 9.81;
    dem::Particles p;
    std::mt19937_64 rng(3);
    auto u = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    // random pour: non-overlapping random positions in a 1.4 m tall column (a lattice stack would be
    // metastable and buckle for seconds)
    std::vector<Vec3> pos;
    std::vector<double> rad;
    while (pos.size() < 216) {
        const double ri = r * (0.95 + 0.1 * u());
        const Vec3 c{ri + (box - 2 * ri) * u(), ri + (box - 2 * ri) * u(), ri + 1.4 * u()};
        bool free = true;
        for (std::size_t q = 0; q < pos.size() && free; ++q) free = norm(pos[q] - c) >= rad[q] + ri;
        if (free) {
            pos.push_back(c);
            rad.push_back(ri);
        }
    }
    for (std::size_t q = 0; q < pos.size(); ++q) p.add_mobile(pos[q], rad[q], rho);
    std::vector<dem::Wall> walls{
        dem::Wall::plane("x0", {0, 0, 0}, {1, 0, 0}), dem::Wall::plane("x1", {box, 0, 0}, {-1, 0, 0}),
        dem::Wall::plane("y0", {0, 0, 0}, {0, 1, 0}), dem::Wall::plane("y1", {0, box, 0}, {0, -1, 0}),
        dem::Wall::plane("bed", {0, 0, 0}, {0, 0, 1})};
    const auto f = dem::friction_from_repose_angle(30.0);
    auto pp = test::linear_law({.kn = 1e6, .restitution = 0.2, .mu_s = f.mu_s, .mu_r = f.mu_r});
    auto pw = test::linear_law({.kn = 1e6, .restitution = 0.2, .mu_s = f.mu_s, .mu_r = 2 * f.mu_r});
    const double tc = pp.normal.contact_time(0.5 * test::mass_of(0.95 * r, rho));
    dem::DemSolver s(p, walls, dem::ContactLawSet<dem::LinearNormal>{pp, pw, pw}, {0, 0, -g}, tc / 20.0,
                     0.01);
    while (s.time() < 4.0) s.step();
    const double m = test::mass_of(r, rho);
    const double energy_scale = 216 * m * g * r;  // potential energy of lifting every grain by r
    const auto ke1 = s.kinetic_energy();
    const std::vector<Vec3> x1 = s.particles().x;
    while (s.time() < 6.0) s.step();
    const auto ke2 = s.kinetic_energy();
    double creep = 0.0;
    for (std::size_t i = 0; i < x1.size(); ++i) creep = std::max(creep, norm(s.particles().x[i] - x1[i]));
    EXPECT_LT(ke1.translational + ke1.rotational, 1e-9 * energy_scale);
    EXPECT_LT(ke2.translational + ke2.rotational, 1e-9 * energy_scale);
    EXPECT_LT(creep, 1e-6 * r) << "largest displacement between t = 4 s and 6 s";
    EXPECT_GT(s.stats().contacts, 216u) << "the grains must form a packed pile";
}

}  // namespace
}  // namespace sabo
