// SPDX-License-Identifier: MIT
// The vector loops of contact_batch.h must give exactly (bit for bit) what the scalar contact law gives
// for each contact: sticking and slipping springs, springs to rotate, clipped and capped lanes.
#include "dem/contact_batch.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace sabo::dem {
namespace {

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
void expect_same(const Vec3& a, const Vec3& b, const char* what, std::uint32_t lane) {
    EXPECT_TRUE(same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z))
        << what << " lane " << lane << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", "
        << b.y << ", " << b.z << ")";
}

Vec3 random_vec(std::mt19937_64& rng, double scale) {
    std::uniform_real_distribution<double> u(-scale, scale);
    return {u(rng), u(rng), u(rng)};
}

template <class Normal>
void check_contact_batch(const ContactLaw<Normal>& law) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double dt = 1e-5;
    ContactBatch b;
    TangentialState hist[batch_capacity];
    Vec3 roll[batch_capacity];
    const std::uint32_t n = batch_capacity - 3;  // a partial batch: the vector loop's remainder too
    for (std::uint32_t h = 0; h < n; ++h) {
        b.ri[h] = 0.045 + 0.01 * u(rng);
        b.rj[h] = 0.045 + 0.01 * u(rng);
        const double overlap = 0.002 * u(rng);
        const Vec3 dir = random_vec(rng, 1.0);
        b.d.set(h, dir * ((b.ri[h] + b.rj[h] - overlap) / norm(dir)));
        b.dv.set(h, random_vec(rng, h % 3 == 0 ? 5.0 : 0.05));  // fast lanes slip, or separate (clip)
        b.rw.set(h, random_vec(rng, 0.1));
        b.inv_m_sum[h] = 1.0 / 1.3 + 1.0 / (1.0 + u(rng));
        hist[h] = {h % 4 == 0 ? Vec3{} : random_vec(rng, 1e-4), static_cast<std::uint8_t>(h % 2)};
        roll[h] = random_vec(rng, h % 5 == 0 ? 10.0 : 1e-3);  // some above the cap
        b.set_state(h, hist[h], roll[h]);
    }
    const ContactBatch input = b;
    evaluate(law, b, n, dt);
    int slipped = 0, capped = 0;
    for (std::uint32_t h = 0; h < n; ++h) {
        ContactBatch one = input;
        evaluate_lane(law, one, h, dt);  // the scalar path, lane by lane
        EXPECT_EQ(b.ok[h], 1.0);
        expect_same(b.pair_force(h).force, one.pair_force(h).force, "force", h);
        expect_same(b.pair_force(h).n_cross_ft, one.pair_force(h).n_cross_ft, "n x F_t", h);
        EXPECT_TRUE(same_bits(b.fn[h], one.fn[h])) << h;
        expect_same(b.xi.get(h), one.xi.get(h), "spring", h);
        EXPECT_EQ(b.sliding[h], one.sliding[h]) << h;
        expect_same(b.roll.get(h), one.roll.get(h), "rolling torque", h);
        // and both are the documented contact law on TangentialState
        TangentialState s = hist[h];
        const double dist = norm(input.d.get(h));
        const double rs = input.ri[h] + input.rj[h];
        const PairForce pf =
            pair_force(law, s, input.d.get(h) / dist, rs - dist, input.dv.get(h), input.rw.get(h),
                       1.0 / input.inv_m_sum[h], input.ri[h] * input.rj[h] / rs, dt);
        expect_same(pf.force, b.pair_force(h).force, "pair_force", h);
        expect_same(s.xi, b.xi.get(h), "pair_force spring", h);
        slipped += s.sliding;
        capped += norm2(roll[h]) > norm2(b.roll.get(h)) ? 1 : 0;
    }
    EXPECT_GT(slipped, 0);  // the sample covers both friction branches and the rolling cap
    EXPECT_LT(slipped, static_cast<int>(n));
    EXPECT_GT(capped, 0);
}

TEST(ContactBatch, LinearLanesEqualScalarContacts) {
    ContactLaw<LinearNormal> law;
    law.normal = {1e6, 0.456, 2.0 / 7.0, true};
    law.tangential = {1.0, 0.577, 0.519, FrictionMemory::hysteresis};
    law.rolling = {0.0678};
    check_contact_batch(law);
}

TEST(ContactBatch, HertzLanesEqualScalarContacts) {
    ContactLaw<HertzNormal> law;
    law.normal = {3.5e7, 1.4e7, 0.45, true, 2.0 / 7.0, true};
    law.tangential = {0.5, 0.4, 0.36, FrictionMemory::hysteresis};
    law.rolling = {0.02};
    check_contact_batch(law);
}

TEST(ContactBatch, RollingUpdateEqualsScalar) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    RollingBatch b;
    const std::uint32_t n = batch_capacity - 1;
    for (std::uint32_t h = 0; h < n; ++h) {
        b.m.set(h, random_vec(rng, 1e-2));
        b.w_rel.set(h, random_vec(rng, h % 2 == 0 ? 10.0 : 1e-3));
        b.split_inv_j[h] = 3.0 * (1.0 + u(rng)) * 1e3;
        b.ri[h] = 0.05;
        b.rj[h] = 0.04 + 0.02 * u(rng);
        b.fn[h] = 10.0 * u(rng);
        b.mu_r[h] = h % 7 == 0 ? 0.0 : 0.0678;
    }
    const RollingBatch input = b;
    update(b, n, 1e-4);
    for (std::uint32_t h = 0; h < n; ++h) {
        const double a_r = input.ri[h] * input.rj[h] / (input.ri[h] + input.rj[h]);
        const Vec3 m =
            ConstantTorqueRolling::update(input.m.get(h), input.w_rel.get(h), input.split_inv_j[h], 1e-4,
                                          ConstantTorqueRolling{input.mu_r[h]}.cap(input.fn[h], a_r));
        expect_same(b.m.get(h), m, "rolling torque", h);
    }
}

}  // namespace
}  // namespace sabo::dem
