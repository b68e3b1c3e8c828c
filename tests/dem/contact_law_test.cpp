// SPDX-License-Identifier: MIT
#include "dem/contact_law.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sabo::dem {

TEST(ContactLaw, DampingRatioFromRestitution) {
    // α(ζ=0.2) = −ln 0.2 / sqrt(ln² 0.2 + π²) = 0.45595 (the value the peer inputs use)
    EXPECT_NEAR(damping_ratio_from_restitution(0.2), 0.455950, 1e-6);
    EXPECT_DOUBLE_EQ(damping_ratio_from_restitution(1.0), 0.0);
}

TEST(ContactLaw, ClippedRestitutionMatchesSchwagerPoeschel) {
    // SPEC §1.2: e ≈ 0.325 for ζ = 0.2
    EXPECT_NEAR(clipped_linear_restitution(damping_ratio_from_restitution(0.2)), 0.325, 5e-4);
    // the 1D numerical reference agrees with the closed form for several ζ
    for (double zeta : {0.02, 0.1, 0.2, 0.5, 0.8}) {  // 0.02: α_n = 0.78, past 1/√2
        LinearNormal law{1e6, damping_ratio_from_restitution(zeta), 2.0 / 7.0, true};
        const double tc = law.contact_time(0.5);
        EXPECT_NEAR(effective_restitution(law, 0.5, 0.025, 2.0, tc), clipped_linear_restitution(law.alpha_n),
                    1e-4)
            << "zeta " << zeta;
        law.clip_attractive = false;
        EXPECT_NEAR(effective_restitution(law, 0.5, 0.025, 2.0, tc), zeta, 1e-4) << "zeta " << zeta;
    }
}

TEST(ContactLaw, LinearForceClipsAttraction) {
    const LinearNormal law{1000.0, 0.5, 2.0 / 7.0, true};
    EXPECT_DOUBLE_EQ(law.force(0.01, 0.0, 1.0, 0.1).fn, 10.0);
    EXPECT_DOUBLE_EQ(law.force(0.001, -100.0, 1.0, 0.1).fn, 0.0);  // separating fast: clipped
    const LinearNormal unclipped{1000.0, 0.5, 2.0 / 7.0, false};
    EXPECT_LT(unclipped.force(0.001, -100.0, 1.0, 0.1).fn, 0.0);
    EXPECT_DOUBLE_EQ(law.force(0.01, 0.0, 1.0, 0.1).kt, 1000.0 * 2.0 / 7.0);
}

TEST(ContactLaw, HertzElasticForceAndMindlinStiffness) {
    HertzNormal law;
    law.e_star = 1e8;
    law.g_star = 4e7;
    law.beta = 0.0;
    const double d = 1e-4, r = 0.05;
    const auto res = law.force(d, 0.0, 1.0, r);
    EXPECT_NEAR(res.fn, 4.0 / 3.0 * 1e8 * std::sqrt(r * d) * d, 1e-9);
    EXPECT_NEAR(res.kt, 8.0 * 4e7 * std::sqrt(r * d), 1e-6);
}

TEST(LudingFriction, SticksBelowStaticLimitAndSlidesAbove) {
    const LudingFriction f{0.0, 0.5, 0.45, FrictionMemory::hysteresis};
    const Vec3 n{0, 0, 1};
    const double kt = 1000.0, fn = 10.0, dt = 1e-3;
    TangentialState s;
    s.xi = {0.004, 0, 0};  // |F_test| = 4 N ≤ μ_s F_n = 5 N
    Vec3 ft = f.force(s, n, {}, fn, kt, 1.0, dt);
    EXPECT_EQ(s.sliding, 0);
    EXPECT_NEAR(ft.x, -4.0, 1e-12);
    s.xi = {0.006, 0, 0};  // 6 N > 5 N: slip at μ_d F_n = 4.5 N, spring reset to the Coulomb limit
    ft = f.force(s, n, {}, fn, kt, 1.0, dt);
    EXPECT_EQ(s.sliding, 1);
    EXPECT_NEAR(ft.x, -4.5, 1e-12);
    EXPECT_NEAR(s.xi.x, 0.0045, 1e-12);
}

TEST(LudingFriction, HysteresisKeepsSlidingUntilBelowDynamicLimit) {
    const Vec3 n{0, 0, 1};
    for (auto memory : {FrictionMemory::hysteresis, FrictionMemory::none}) {
        const LudingFriction f{0.0, 0.5, 0.45, memory};
        TangentialState s;
        s.sliding = 1;
        s.xi = {0.0047, 0, 0};  // 4.7 N: between μ_d F_n = 4.5 N and μ_s F_n = 5 N
        const Vec3 ft = f.force(s, n, {}, 10.0, 1000.0, 1.0, 1e-3);
        if (memory == FrictionMemory::hysteresis) {
            EXPECT_EQ(s.sliding, 1);
            EXPECT_NEAR(ft.x, -4.5, 1e-12);
        } else {
            EXPECT_EQ(s.sliding, 0);
            EXPECT_NEAR(ft.x, -4.7, 1e-12);
        }
    }
}

TEST(LudingFriction, SpringIsRotatedIntoTheNewTangentPlaneKeepingItsLength) {
    const LudingFriction f{0.0, 10.0, 9.0, FrictionMemory::hysteresis};
    TangentialState s;
    s.xi = {0.003, 0, 0.004};  // length 0.005, not in the plane normal to z
    const Vec3 ft = f.force(s, {0, 0, 1}, {}, 100.0, 1000.0, 1.0, 1e-3);
    EXPECT_NEAR(ft.x, -5.0, 1e-12);  // rotated to (0.005, 0, 0)
    EXPECT_NEAR(ft.z, 0.0, 1e-12);
}

TEST(ConstantTorqueRolling, RollingContactGetsTheConstantTorqueOpposingTheRotation) {
    const ConstantTorqueRolling roll{0.1};
    const double cap = roll.cap(100.0, 0.05);
    EXPECT_DOUBLE_EQ(cap, 0.1 * 100.0 * 0.05);  // μ_r F_n A_r
    // fast relative rotation: the torque is the cap, opposite to ω_rel, whatever the warm start
    const Vec3 w{0, 2.0, 0};
    for (const Vec3 warm : {Vec3{}, Vec3{0, -0.5, 0}, Vec3{0.3, 0, 0}}) {
        const Vec3 m = ConstantTorqueRolling::update(warm, w, 1.0, 1e-6, cap);
        EXPECT_NEAR(norm(m), cap, 1e-12);
        EXPECT_NEAR(m.y, -cap, 1e-6 * cap);
    }
}

TEST(ConstantTorqueRolling, StopsASlowRotationExactlyWithoutReversingIt) {
    const ConstantTorqueRolling roll{0.1};
    const double cap = roll.cap(100.0, 0.05), inv_j = 2.0, dt = 1e-3;
    const Vec3 w{0, 1.0, 0};  // stopping it over dt needs the torque 1/(inv_j dt) = 500
    const double big_cap = 1000.0;
    const Vec3 m = ConstantTorqueRolling::update({}, w, inv_j, dt, big_cap);
    EXPECT_NEAR(w.y + dt * inv_j * m.y, 0.0, 1e-12);  // within the cap: stopped exactly
    // beyond the cap the torque saturates and ω_rel keeps its sign
    const Vec3 m_small = ConstantTorqueRolling::update({}, w, inv_j, dt, cap);
    EXPECT_NEAR(m_small.y, -cap, 1e-12);
    EXPECT_GT(w.y + dt * inv_j * m_small.y, 0.0);
    // a grain at rest relative to its partner keeps its warm-started torque (the constraint holds)
    const Vec3 held{0.2, -0.1, 0};
    const Vec3 m_held = ConstantTorqueRolling::update(held, {}, inv_j, dt, cap);
    EXPECT_EQ(m_held.x, held.x);
    EXPECT_EQ(m_held.y, held.y);
    // and a warm start above a reduced cap (lower normal force) is clamped, direction kept
    const Vec3 m_clamped = ConstantTorqueRolling::clamp_norm({3.0, 4.0, 0.0}, 1.0);
    EXPECT_NEAR(m_clamped.x, 0.6, 1e-15);
    EXPECT_NEAR(m_clamped.y, 0.8, 1e-15);
}

// The two models differ only in the torque a contact starts its step with: the last one within the new
// cap (constraint) or none (directional: SPEC's torque, −min(cap, |ω_rel|/(Δt Σ s/J)) ω̂_rel, from ω_rel
// alone).
TEST(ConstantTorqueRolling, TheDirectionalModelStartsEachStepWithoutTorque) {
    const Vec3 last{0.3, -0.4, 0.0};
    const ConstantTorqueRolling constraint{0.1, RollingModel::constraint};
    const ConstantTorqueRolling directional{0.1, RollingModel::directional};
    const Vec3 kept = constraint.start(last, 100.0, 0.05);  // cap 0.5: kept as it is
    EXPECT_EQ(kept.x, last.x);
    EXPECT_EQ(kept.y, last.y);
    const Vec3 clamped = constraint.start(last, 50.0, 0.05);  // cap 0.25: scaled down
    EXPECT_NEAR(norm(clamped), 0.25, 1e-15);
    EXPECT_EQ(norm2(directional.start(last, 100.0, 0.05)), 0.0);
    // from no torque, one update is SPEC's: the cap while it rolls, the stopping torque below it
    const double inv_j = 2.0, dt = 1e-3;
    const Vec3 fast{0, 10.0, 0}, slow{0, 0.1, 0};  // stopping them needs 5000 and 50
    EXPECT_NEAR(ConstantTorqueRolling::update(directional.start(last, 100.0, 0.05), fast, inv_j, dt, 0.5).y,
                -0.5, 1e-15);
    EXPECT_NEAR(ConstantTorqueRolling::update(directional.start(last, 100.0, 0.05), slow, inv_j, dt, 500.0).y,
                -50.0, 1e-12);
}

}  // namespace sabo::dem
