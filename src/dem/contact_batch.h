// SPDX-License-Identifier: MIT
// A batch of particle–particle contacts evaluated as one vector loop. The force pass gathers the inputs
// of up to `batch_capacity` touching pairs (scalar loads: the partners are scattered in memory), evaluates
// them here with the same pair_force() the scalar code uses, lanes in parallel, and then sums the results
// in list order. The contact laws are written without branches, and FMA contraction is off for the
// whole build, so a lane rounds exactly as the scalar call would: batching changes no bit of the result.
// (Latency, not arithmetic, bounded the one-contact-at-a-time loop: each contact is a chain of three
// square roots and three divisions; a vector of contacts runs those chains side by side.)
#pragma once
#include <cmath>
#include <cstdint>

#include "core/vec3.h"
#include "dem/contact_law.h"

namespace sabo::dem {

// Contacts per batch (the force pass screens its list entries in chunks of this size).
inline constexpr std::uint32_t batch_capacity = 32;
using Lanes = double[batch_capacity];
// Three lanes arrays (the vectoriser does not take whole-Vec3 copies).
struct Vec3Lanes {
    Lanes x, y, z;
    [[nodiscard]] Vec3 get(std::uint32_t h) const { return {x[h], y[h], z[h]}; }
    void set(std::uint32_t h, const Vec3& v) {
        x[h] = v.x;
        y[h] = v.y;
        z[h] = v.z;
    }
};

// Normal and tangential forces of particle–particle contacts; structure of arrays, one lane per contact.
struct ContactBatch {
    // inputs
    Vec3Lanes d;   // x_j − x_i
    Vec3Lanes dv;  // v_i − v_j (half-step velocities)
    Vec3Lanes rw;  // r_i ω_i + r_j ω_j
    Lanes ri, rj;
    Lanes inv_m_sum;  // 1/m_i + 1/m_j
    // in and out: tangential spring and slip state (1 or 0), last step's rolling torque → clamped
    Vec3Lanes xi;
    Lanes sliding;
    Vec3Lanes roll;
    // outputs
    Vec3Lanes force, n_cross_ft;  // PairForce
    Lanes fn;
    Lanes delta;  // overlap
    Lanes ok;     // 0: coincident centres or a non-finite distance (the lane is garbage)

    void set_state(std::uint32_t h, const TangentialState& s, const Vec3& m) {
        xi.set(h, s.xi);
        sliding[h] = s.sliding;
        roll.set(h, m);
    }
    [[nodiscard]] TangentialState state(std::uint32_t h) const {
        return {xi.get(h), static_cast<std::uint8_t>(sliding[h] != 0.0 ? 1 : 0)};
    }
    [[nodiscard]] PairForce pair_force(std::uint32_t h) const {
        return {force.get(h), n_cross_ft.get(h), fn[h]};
    }
};

// Evaluates lane h with `law`, whose rolling model is `Model` (a template parameter: the vector loop
// carries no select for it); r_eff = r_i r_j/(r_i + r_j), m̃ = 1/(1/m_i + 1/m_j).
template <RollingModel Model, class Normal>
[[gnu::always_inline]] inline void evaluate_one(const ContactLaw<Normal>& law, ContactBatch& b,
                                                std::uint32_t h, double dt) {
    const double rs = b.ri[h] + b.rj[h];
    const Vec3 d = b.d.get(h);
    const double dist = std::sqrt(norm2(d));
    b.ok[h] = dist > 1e-9 * rs ? 1.0 : 0.0;
    const double delta = rs - dist;
    const double r_eff = b.ri[h] * b.rj[h] / rs;
    Vec3 xi_new;
    double sliding_new = 0.0;
    const PairForce pf = pair_force(law, b.xi.get(h), b.sliding[h], d / dist, delta, b.dv.get(h), b.rw.get(h),
                                    1.0 / b.inv_m_sum[h], r_eff, dt, xi_new, sliding_new);
    b.xi.set(h, xi_new);
    b.sliding[h] = sliding_new;
    b.roll.set(h, law.rolling.template start<Model>(b.roll.get(h), pf.fn, r_eff));
    b.force.set(h, pf.force);
    b.n_cross_ft.set(h, pf.n_cross_ft);
    b.fn[h] = pf.fn;
    b.delta[h] = delta;
}

// Evaluates lanes [0, n) with one law, as a vector loop.
template <class Normal>
inline void evaluate(const ContactLaw<Normal>& law, ContactBatch& b, std::uint32_t n, double dt) {
    const ContactLaw<Normal> local = law;  // coefficients in registers, not conditional loads
    if (local.rolling.model == RollingModel::constraint) {
#pragma omp simd
        for (std::uint32_t h = 0; h < n; ++h) evaluate_one<RollingModel::constraint>(local, b, h, dt);
    } else {
#pragma omp simd
        for (std::uint32_t h = 0; h < n; ++h) evaluate_one<RollingModel::directional>(local, b, h, dt);
    }
}

// One lane, the rolling model chosen at run time (the odd contact outside the vector loop).
template <class Normal>
inline void evaluate_lane(const ContactLaw<Normal>& law, ContactBatch& b, std::uint32_t h, double dt) {
    if (law.rolling.model == RollingModel::constraint)
        evaluate_one<RollingModel::constraint>(law, b, h, dt);
    else
        evaluate_one<RollingModel::directional>(law, b, h, dt);
}

// One projected Jacobi update of the rolling torques of particle–particle contacts
// (ConstantTorqueRolling::update with cap μ_r F_n A_r, A_r = r_i r_j/(r_i + r_j)).
struct RollingBatch {
    Vec3Lanes m;      // in: the contact's torque on i; out: updated
    Vec3Lanes w_rel;  // ω_i − ω_j
    Lanes split_inv_j;
    Lanes ri, rj, fn, mu_r;
};

inline void update(RollingBatch& b, std::uint32_t n, double dt) {
#pragma omp simd
    for (std::uint32_t h = 0; h < n; ++h) {
        const double a_r = b.ri[h] * b.rj[h] / (b.ri[h] + b.rj[h]);
        b.m.set(h, ConstantTorqueRolling::update(b.m.get(h), b.w_rel.get(h), b.split_inv_j[h], dt,
                                                 ConstantTorqueRolling::cap(b.mu_r[h], b.fn[h], a_r)));
    }
}

}  // namespace sabo::dem
