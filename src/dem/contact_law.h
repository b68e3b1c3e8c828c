// SPDX-License-Identifier: MIT
// Contact laws of docs/dem.md, each a small value type with its coefficients (SI units) and one
// force() function (rolling resistance: cap() and update()). A ContactLaw<Normal> composes a normal law with
// the Luding tangential law and the directional constant rolling resistance; the hot kernel (pair_force) is
// templated on the normal law so the choice costs nothing inside the loop.
//
// Sign conventions (docs/dem.md): n points from i to j; v_rel is the velocity of i relative to j at
// the contact point; v_n = v_rel·n > 0 while approaching. Returned forces act on i.
#pragma once
#include <cmath>
#include <cstdint>

#include "core/vec3.h"

namespace sabo::dem {

// Damping ratio from the restitution coefficient ζ: α = −ln ζ / sqrt(ln²ζ + π²).
[[nodiscard]] double damping_ratio_from_restitution(double restitution);

// Restitution of the linear spring–dashpot when attractive forces are clipped (Schwager & Pöschel
// 2007); valid for α < 1/sqrt(2).
[[nodiscard]] double clipped_linear_restitution(double alpha);

struct NormalResult {
    double fn;  // normal force magnitude, N (clipped ≥ 0 unless clipping is off)
    double kt;  // tangential stiffness for this contact, N/m
};

// Linear spring–dashpot: F_n = k_n δ + 2 α_n sqrt(k_n m̃) v_n.   k_n [N/m], α_n [-], k_t = ratio·k_n.
struct LinearNormal {
    double kn = 0.0;
    double alpha_n = 0.0;
    double kt_ratio = 2.0 / 7.0;
    bool clip_attractive = true;

    [[nodiscard]] NormalResult force(double delta, double vn, double m_eff, double /*r_eff*/) const {
        double fn = kn * delta + 2.0 * alpha_n * std::sqrt(kn * m_eff) * vn;
        if (clip_attractive && fn < 0.0) fn = 0.0;
        return {fn, kt_ratio * kn};
    }
    // t_c = π / sqrt(k_n/m̃ (1 − α_n²))
    [[nodiscard]] double contact_time(double m_eff) const;
    // elastic energy stored at overlap δ: k_n δ²/2; tangential stiffness at that overlap
    [[nodiscard]] double potential(double delta, double /*r_eff*/) const { return 0.5 * kn * delta * delta; }
    [[nodiscard]] double tangential_stiffness(double /*delta*/, double /*r_eff*/) const {
        return kt_ratio * kn;
    }
};

// Hertz with Tsuji damping in the LIGGGHTS form:
//   F_n = 4/3 E* sqrt(r̃δ) δ + 2 sqrt(5/6) β sqrt(S_n m̃) v_n,  S_n = 2 E* sqrt(r̃δ).
// E*, G* [Pa]; tangential stiffness Mindlin k_t = 8 G* sqrt(r̃δ), or ratio · 4/3 E* sqrt(r̃δ).
struct HertzNormal {
    double e_star = 0.0;
    double g_star = 0.0;
    double beta = 0.0;
    bool mindlin = true;
    double kt_ratio = 2.0 / 7.0;
    bool clip_attractive = true;

    [[nodiscard]] NormalResult force(double delta, double vn, double m_eff, double r_eff) const {
        const double a = std::sqrt(r_eff * delta);
        const double sn = 2.0 * e_star * a;
        constexpr double k_damp = 1.8257418583505538;  // 2 sqrt(5/6)
        double fn = (4.0 / 3.0) * e_star * a * delta + k_damp * beta * std::sqrt(sn * m_eff) * vn;
        if (clip_attractive && fn < 0.0) fn = 0.0;
        const double kt = mindlin ? 8.0 * g_star * a : kt_ratio * (4.0 / 3.0) * e_star * a;
        return {fn, kt};
    }
    // Elastic Hertz duration t_c = 2.868 (m̃² / (r̃ E*² v))^{1/5} for impact speed v (equals the reference
    // model's 2.214 (ρ/E*)^{2/5} d / v^{1/5} for identical spheres).
    [[nodiscard]] double contact_time(double m_eff, double r_eff, double impact_speed) const;
    // elastic energy stored at overlap δ: 8/15 E* sqrt(r̃) δ^{5/2}; tangential stiffness at δ
    [[nodiscard]] double potential(double delta, double r_eff) const {
        return 8.0 / 15.0 * e_star * std::sqrt(r_eff) * std::pow(delta, 2.5);
    }
    [[nodiscard]] double tangential_stiffness(double delta, double r_eff) const {
        const double a = std::sqrt(r_eff * delta);
        return mindlin ? 8.0 * g_star * a : kt_ratio * (4.0 / 3.0) * e_star * a;
    }
};

enum class FrictionMemory : std::uint8_t { hysteresis, none };

// Per-contact tangential history: spring ξ [m] and stick/slip state.
struct TangentialState {
    Vec3 xi{};
    std::uint8_t sliding = 0;
};

// Luding (2008) tangential spring with static/dynamic Coulomb limits (docs/dem.md).
// α_t [-] tangential damping ratio; μ_s, μ_d [-].
struct LudingFriction {
    double alpha_t = 1.0;
    double mu_s = 0.0;
    double mu_d = 0.0;
    FrictionMemory memory = FrictionMemory::hysteresis;

    // The law on plain values (one contact, or one lane of a vector loop): spring ξ and slip state
    // (1 sliding, 0 sticking; a double so that a vector lane keeps it with the other lanes) in, updated
    // ξ and slip state out.
    [[nodiscard]] Vec3 force(const Vec3& xi, double sliding_in, const Vec3& n, const Vec3& vt, double fn,
                             double kt, double m_eff, double dt, Vec3& xi_out, double& sliding_out) const {
        // 1. rotate the old spring into the current tangent plane, keeping its length (a spring of
        // zero length, or one normal to the plane, is dropped)
        const double len2 = norm2(xi);
        const Vec3 xp = xi - n * dot(n, xi);
        const double lp = norm(xp);
        const bool keep = lp >= 1e-14;
        const double scale = std::sqrt(len2) / lp;
        Vec3 xs{keep ? xp.x * scale : 0.0, keep ? xp.y * scale : 0.0, keep ? xp.z * scale : 0.0};
        // 2. advance the spring by this step's tangential displacement, then the trial force. (the reference
        // model writes the increment after the force; that makes the force lag the displacement by one step,
        // which anti-damps the tangential oscillation by ~(ω_t Δt)² per step — docs/dem.md.)
        xs += vt * dt;
        const double ct = 2.0 * alpha_t * std::sqrt(kt * m_eff);
        const Vec3 f_test = -kt * xs - ct * vt;
        const double ft = norm(f_test);
        // 3. stick/slip with hysteresis (a sliding contact re-sticks only below μ_d F_n); a slipping
        // spring is reset to the length that gives the sliding force
        const bool was_sliding = sliding_in != 0.0 && memory == FrictionMemory::hysteresis;
        const bool stick = (was_sliding ? ft < mu_d * fn : ft <= mu_s * fn) || ft == 0.0;
        const double to_slip = stick ? 1.0 : mu_d * fn / ft;  // f_test · 1 is exact
        const Vec3 f = f_test * to_slip;
        const Vec3 xi_slip = -(f + ct * vt) / kt;
        xi_out = {stick ? xs.x : xi_slip.x, stick ? xs.y : xi_slip.y, stick ? xs.z : xi_slip.z};
        sliding_out = stick ? 0.0 : 1.0;
        return f;
    }
    [[nodiscard]] Vec3 force(TangentialState& s, const Vec3& n, const Vec3& vt, double fn, double kt,
                             double m_eff, double dt) const {
        double sliding = 0.0;
        const Vec3 f = force(s.xi, s.sliding, n, vt, fn, kt, m_eff, dt, s.xi, sliding);
        s.sliding = sliding != 0.0 ? 1 : 0;
        return f;
    }
};

// How a contact's rolling torque is found (dem.rolling_model; docs/dem.md, "Rolling resistance").
enum class RollingModel : std::uint8_t {
    // a constraint torque, warm-started from the last step: holds a static torque up to the cap
    constraint,
    // docs/dem.md as written: computed afresh each step from ω_rel, never reversing it within the step
    directional,
};

// Directional constant rolling torque (model "b", docs/dem.md), μ_r [-] fraction of the rolling
// radius A_r: M_r,i = −μ_r F_n A_r ω_rel/|ω_rel|, never reversing ω_rel within a step.
// Both models do it with one projected Jacobi update per step that moves M towards the torque that
// stops ω_rel over one step and clamps it to |M| ≤ μ_r F_n A_r:
// - constraint: each contact keeps the torque M it exerted in the last step (warm start) and the update
//   starts from it; a torque within the cap is held, so a deposit at rest stays at rest;
// - directional: the update starts from M = 0, so M = −min(μ_r F_n A_r, |ω_rel| / (Δt Σ s/J)) ω̂_rel:
//   the reference torque with its cap against reversal (s: the grains' contact counts, below).
// While the contact rolls the clamp is active and M = −μ_r F_n A_r ω̂_rel (to O(cap/|ω_rel|)) in both.
struct ConstantTorqueRolling {
    double mu_r = 0.0;
    RollingModel model = RollingModel::constraint;

    // Largest rolling torque of a contact, N·m: μ_r F_n A_r. The static form serves vector loops that
    // carry μ_r per lane (a law object built inside such a loop, with its model member, keeps GCC from
    // vectorising it).
    [[nodiscard]] static double cap(double mu_r, double fn, double a_r) { return mu_r * fn * a_r; }
    [[nodiscard]] double cap(double fn, double a_r) const { return cap(mu_r, fn, a_r); }

    // Torque on i after one update: `split_inv_j` is the contact's share of the inverse inertias,
    // s_i/J_i + s_j/J_j with s the number of contacts of each grain (mass splitting: the updates of
    // all contacts of a grain together at most stop its rotation, so Jacobi sweeps never overshoot).
    [[nodiscard]] static Vec3 update(const Vec3& m, const Vec3& w_rel, double split_inv_j, double dt,
                                     double cap) {
        return clamp_norm(m - w_rel / (split_inv_j * dt), cap);
    }

    // The torque a contact starts its step with, given the last step's and the new normal force: the last
    // one within the new cap (constraint), none (directional). The template form lets a vector loop over
    // contacts of one law leave the model out of the loop.
    template <RollingModel Model>
    [[nodiscard]] Vec3 start(const Vec3& last, double fn, double a_r) const {
        if constexpr (Model == RollingModel::constraint)
            return clamp_norm(last, cap(fn, a_r));
        else
            return Vec3{};
    }
    [[nodiscard]] Vec3 start(const Vec3& last, double fn, double a_r) const {
        return model == RollingModel::constraint ? start<RollingModel::constraint>(last, fn, a_r)
                                                 : start<RollingModel::directional>(last, fn, a_r);
    }

    // |m| ≤ cap, keeping the direction.
    [[nodiscard]] static Vec3 clamp_norm(const Vec3& m, double cap) {
        const double m2 = norm2(m);
        return m * (m2 <= cap * cap ? 1.0 : cap / std::sqrt(m2));  // m · 1 is exact
    }
};

template <class Normal>
struct ContactLaw {
    Normal normal;
    LudingFriction tangential;
    ConstantTorqueRolling rolling;
};

// The three interaction classes of a simulation share one normal-law type.
template <class Normal>
struct ContactLawSet {
    ContactLaw<Normal> particle_particle;
    ContactLaw<Normal> particle_wall;
    ContactLaw<Normal> particle_barrier;
};

// Normal and tangential part of one contact, forces on i. Rolling resistance is handled by the
// solver (ConstantTorqueRolling).
struct PairForce {
    Vec3 force;       // F_t − F_n n
    Vec3 n_cross_ft;  // n × F_t: torque on i is r_i n×F_t, on j r_j n×F_t
    double fn;
};

// One contact: n (i→j), overlap δ > 0, dv = v_i − v_j, rw = r_i ω_i + r_j ω_j (wall: r_i ω_i), m̃, r̃;
// the tangential spring ξ and slip state in, updated ones out (plain values: also one lane of a
// vector loop, contact_batch.h).
template <class Normal>
[[nodiscard]] inline PairForce pair_force(const ContactLaw<Normal>& law, const Vec3& xi, double sliding,
                                          const Vec3& n, double delta, const Vec3& dv, const Vec3& rw,
                                          double m_eff, double r_eff, double dt, Vec3& xi_out,
                                          double& sliding_out) {
    const Vec3 v_rel = dv + cross(rw, n);
    const double vn = dot(v_rel, n);
    const Vec3 vt = v_rel - n * vn;
    const NormalResult nr = law.normal.force(delta, vn, m_eff, r_eff);
    const Vec3 ft = law.tangential.force(xi, sliding, n, vt, nr.fn, nr.kt, m_eff, dt, xi_out, sliding_out);
    return {ft - n * nr.fn, cross(n, ft), nr.fn};
}

// The same with the history kept in a TangentialState.
template <class Normal>
[[nodiscard]] inline PairForce pair_force(const ContactLaw<Normal>& law, TangentialState& state,
                                          const Vec3& n, double delta, const Vec3& dv, const Vec3& rw,
                                          double m_eff, double r_eff, double dt) {
    double sliding = 0.0;
    const PairForce pf =
        pair_force(law, state.xi, state.sliding, n, delta, dv, rw, m_eff, r_eff, dt, state.xi, sliding);
    state.sliding = sliding != 0.0 ? 1 : 0;
    return pf;
}

// Numerical restitution of a head-on normal impact at speed v (1D integration of m̃ δ'' = −F_n with
// RK4 and a step of t_c/20000): the "effective e" reported at start-up, valid for any normal law.
template <class Normal>
[[nodiscard]] double effective_restitution(const Normal& law, double m_eff, double r_eff, double impact_speed,
                                           double contact_time);

}  // namespace sabo::dem
