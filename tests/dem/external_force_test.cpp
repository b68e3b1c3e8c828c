// SPDX-License-Identifier: MIT
// The DEM solver's external force and torque slot (the fluid's share in a coupled run): it accelerates and
// spins each grain as Newton–Euler says, and stays with its grain when grains are reordered and removed.
#include <gtest/gtest.h>

#include <vector>

#include "dem/test_support.h"

namespace sabo {
namespace {

constexpr double r = 0.05, rho = 2500.0;

TEST(ExternalForce, AConstantForceAndTorqueActAsNewtonEulerSays) {
    dem::Particles p;
    p.add_mobile({0, 0, 0}, r, rho);
    const double dt = 1e-4;
    dem::DemSolver s(p, {}, test::same_everywhere(test::linear_law({})), {0, 0, -9.81}, dt, 0.01);
    const Vec3 force{2.0, -1.0, 0.5}, torque{0.0, 0.03, -0.01};
    s.set_external_forces(std::vector<Vec3>{force}, std::vector<Vec3>{torque});
    for (int k = 0; k < 1000; ++k) s.step();
    const double m = test::mass_of(r, rho), j = 0.4 * m * r * r, t = s.time();
    const Vec3 a = force * (1.0 / m) + Vec3{0, 0, -9.81};
    const auto& q = s.particles();
    // velocity Verlet is exact for a constant force: x = a t²/2, v = a t; ω = T t / J
    EXPECT_NEAR(q.x[0].x, 0.5 * a.x * t * t, 1e-12);
    EXPECT_NEAR(q.x[0].z, 0.5 * a.z * t * t, 1e-12);
    EXPECT_NEAR(q.v[0].y, a.y * t, 1e-12);
    EXPECT_NEAR(q.w[0].y, torque.y * t / j, 1e-9);
    EXPECT_NEAR(q.w[0].z, torque.z * t / j, 1e-9);
    EXPECT_NEAR(q.f[0].x, force.x, 1e-15);  // particles().f includes it (no contact here)
}

TEST(ExternalForce, StaysWithItsGrainThroughReorderingAndRemoval) {
    // grains far apart on a 6 x 6 grid, each pushed along X by a force of its own: after reorders and
    // removals every grain that is left still moves with its own force
    dem::Particles p;
    const int n = 36;
    for (int k = 0; k < n; ++k) p.add_mobile({1.0 * (k % 6), 1.0 * (k / 6), 0.0}, r, rho);
    const double dt = 1e-3;
    dem::DemSolver s(p, {}, test::same_everywhere(test::linear_law({})), {}, dt, 0.002);
    s.set_reorder_interval(1);
    const auto push = [](std::uint32_t id) { return Vec3{0.1 * (1 + id % 7), 0.0, 0.01 * id}; };
    std::vector<Vec3> forces(s.mobile_count()), torques(s.mobile_count());
    for (std::size_t i = 0; i < s.mobile_count(); ++i) forces[i] = push(s.ids()[i]);
    s.set_external_forces(forces, torques);
    for (int k = 0; k < 400; ++k) {
        if (k == 150) {  // remove every third grain (by current index)
            std::vector<std::uint8_t> gone(s.mobile_count(), 0);
            for (std::size_t i = 0; i < gone.size(); i += 3) gone[i] = 1;
            s.remove_mobile(gone);
        }
        s.step();
    }
    ASSERT_EQ(s.mobile_count(), 24u);
    ASSERT_GT(s.list_builds(), 5u) << "the grains must have been reordered several times";
    const double m = test::mass_of(r, rho), t = s.time();
    const auto& q = s.particles();
    bool reordered = false;
    for (std::size_t i = 0; i < s.mobile_count(); ++i) {
        const std::uint32_t id = s.ids()[i];
        reordered = reordered || id != i;
        const Vec3 a = push(id) * (1.0 / m);
        EXPECT_NEAR(q.v[i].x, a.x * t, 1e-12) << "grain " << id;
        EXPECT_NEAR(q.v[i].z, a.z * t, 1e-12) << "grain " << id;
        EXPECT_NEAR(q.x[i].x, (id % 6) + 0.5 * a.x * t * t, 1e-12) << "grain " << id;
    }
    EXPECT_TRUE(reordered) << "the test must see grains change index";
}

}  // namespace
}  // namespace sabo
