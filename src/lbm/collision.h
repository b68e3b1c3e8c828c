// SPDX-License-Identifier: MIT
// Internal to the lattice: the BGK–Guo collision of one cell (written once, used by the vectorised
// interior sweep and by the batches of cells next to walls and on the free surface), and the
// moving-wall bounce-back term (fluid_lattice.cpp, free_surface.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>

#include "core/vec3.h"
#include "lbm/d3q19.h"
#include "lbm/rheology.h"

// a lambda the compiler must inline (GCC does not always, for large bodies: the populations would go
// through memory)
#define SABO_ALWAYS_INLINE __attribute__((always_inline))

namespace sabo::lbm::detail {

// Calls body(std::integral_constant<int, p>) for the pairs p = 0..8 of opposite directions (2p + 1,
// 2p + 2): every index below is a compile-time constant, so the components of c_i (0, ±1) fold away.
template <class Body>
[[gnu::always_inline]] inline void for_each_pair(Body&& body) {
    [&]<int... P>(std::integer_sequence<int, P...>) SABO_ALWAYS_INLINE {
        (body(std::integral_constant<int, P>{}), ...);
    }
    (std::make_integer_sequence<int, (Q - 1) / 2>{});
}

// c_i · (x, y, z) with only the non-zero components (D3Q19: one or two, each ±1)
template <int I, class T>
[[gnu::always_inline]] inline T project(T x, T y, T z) {
    constexpr int a = cx[I], b = cy[I], c = cz[I];
    const auto term = [](auto sign, T v) { return sign > 0 ? v : -v; };
    if constexpr (a != 0 && b != 0)
        return term(a, x) + term(b, y);
    else if constexpr (a != 0 && c != 0)
        return term(a, x) + term(c, z);
    else if constexpr (b != 0 && c != 0)
        return term(b, y) + term(c, z);
    else if constexpr (a != 0)
        return term(a, x);
    else if constexpr (b != 0)
        return term(b, y);
    else
        return term(c, z);
}

// v[0] + … + v[N−1] as a balanced tree (the order is fixed: results do not depend on the caller)
template <int N, class T>
[[gnu::always_inline]] inline T tree_sum(const T* v) {
    if constexpr (N == 1)
        return v[0];
    else
        return tree_sum<N / 2>(v) + tree_sum<N - N / 2>(v + N / 2);
}

// Σ_p c_{2p+1, A} d_p over the pairs p whose direction has a non-zero component on axis A, as a tree
template <int A, class T>
[[gnu::always_inline]] inline T axis_sum(const T (&d)[(Q - 1) / 2]) {
    constexpr auto component = [](int i) { return A == 0 ? cx[i] : (A == 1 ? cy[i] : cz[i]); };
    constexpr int count = [&] {
        int c = 0;
        for (int p = 0; p < (Q - 1) / 2; ++p) c += component(2 * p + 1) != 0 ? 1 : 0;
        return c;
    }();
    T terms[count];
    int t = 0;
    for_each_pair([&](auto p) SABO_ALWAYS_INLINE {
        constexpr int c = component(2 * p + 1);
        if constexpr (c != 0) terms[t++] = c > 0 ? d[p] : -d[p];
    });
    return tree_sum<count>(terms);
}

// Sweep constants in the compute type T: body acceleration (force density F = ρ a), Newtonian ω and
// the rheology (Bingham, Smagorinsky).
template <class T>
struct Relaxation {
    T ax = 0, ay = 0, az = 0;
    T omega = 1, tau = 1;  // Newtonian
    T tau_min = 0, tau_max = 1, nu_plastic = 0, yield = 0, smagorinsky = 0;
    Relaxation(const Vec3& accel, const Rheology& rh)
        : ax(static_cast<T>(accel.x)),
          ay(static_cast<T>(accel.y)),
          az(static_cast<T>(accel.z)),
          omega(static_cast<T>(1.0 / rh.tau)),
          tau(static_cast<T>(rh.tau)),
          tau_min(static_cast<T>(rh.tau_min)),
          tau_max(static_cast<T>(rh.tau_max)),
          nu_plastic(static_cast<T>(rh.nu_plastic)),
          yield(static_cast<T>(rh.yield)),
          smagorinsky(static_cast<T>(rh.smagorinsky)) {}
};

// What a cell's collision does with a solid covering it: nothing (no solid), the drag or the partially
// saturated collision (FluidLattice::SolidExchange).
enum class Solid : std::uint8_t { none, drag, psm };

// A cell covered by a grain (the grain–fluid coupling, lattice units): the velocity of the grain's surface
// at the cell's centre, v_p = v + ω × (x − x_p), and the weight B λ (the solid's saturation weight times
// the cell's fill fraction). The collision computes the hydrodynamic force on the grain from this cell,
// F_h: with the drag, B λ ρ (u_f − v_p) with the fluid velocity before any force shift u_f = Σ c_i f_i / ρ,
// the cell's force density being ρ a − F_h (Leonardi et al. 2016, simplified immersed boundary); with the
// partially saturated collision, −B λ Σ c_i Ω^s_i (collide_cell).
template <class T>
struct SolidDrag {
    T vx = 0, vy = 0, vz = 0, weight = 0;  // in
    T hx = 0, hy = 0, hz = 0;              // out: F_h
};

// The grains' side of a vectorised run of cells: lane l's weight at w[l] (1 for a wet grain cell, 0 for a
// cell without grain) and v_p at v[a][l] (in), its F_h at h[a][l] (out), a = x, y, z. Each has a vector's
// worth of readable entries beyond the run (FluidLattice pads them).
template <class T>
struct SolidLanes {
    const T* w = nullptr;
    const T* v[3] = {nullptr, nullptr, nullptr};
    T* h[3] = {nullptr, nullptr, nullptr};
    [[nodiscard]] SolidLanes from(std::size_t l) const {
        return {w + l, {v[0] + l, v[1] + l, v[2] + l}, {h[0] + l, h[1] + l, h[2] + l}};
    }
};

// BGK collision with Guo forcing of one cell, in place. f holds the populations as deviations from
// rest, f_i − w_i (the storage form: small numbers keep their digits in float). With Bingham or Les,
// τ comes from the strain rate of the non-equilibrium moments with the previous τ (tau: in the
// previous, out the new one; clamped −1/0/+1 for τ_min/none/τ_max). C, the type of the clamp
// flag, is the caller's: GCC sizes a loop's vectors by its narrowest type, so the vectorised sweep picks
// the flag's width to set how many cells an iteration takes (FluidLattice::collide_interior). S: what the
// cell does with the grain covering it (drag: the weight 0 for a cell without one).
// The partially saturated collision (Noble & Torczynski 1998), with β = B λ the drag's weight and G_i the
// Guo term of gravity:
//   f_i* = (1 − β) (f_i − ω (f_i − f_i^eq(ρ, u)) + G_i) + β (f_i + Ω^s_i),
//   Ω^s_i = (f_ī − f_ī^eq(ρ, u)) − (f_i − f_i^eq(ρ, v_p))   (the non-equilibrium bounce-back):
// the share β of the cell is solid, relaxed toward the grain's velocity and not weighed (β = 1:
// f_i* = f_i^eq(ρ, v_p) + f_ī^neq); F_h = −β Σ c_i Ω^s_i carries the pressure on that share, its buoyancy
// included, and the coupling adds the weight of the rest of the grain's volume (GrainFluidCoupling).
template <bool Bingham, bool Les, Solid S = Solid::none, class T, class C>
[[gnu::always_inline]] inline void collide_cell(T (&f)[Q], T& tau, C& clamped, const Relaxation<T>& r,
                                                SolidDrag<T>* drag = nullptr) {
    // moments: δρ = Σ (f_i − w_i), j = Σ c_i f_i (Σ w_i c_i = 0), as balanced trees of the pairs' sums
    // and differences (c_ī = −c_i): a chain of 18 additions would bound the vector loop by its latency
    T sums[(Q + 1) / 2], diffs[(Q - 1) / 2];
    sums[(Q - 1) / 2] = f[0];
    for_each_pair([&](auto p) SABO_ALWAYS_INLINE {
        constexpr int i = 2 * p + 1;
        sums[p] = f[i] + f[i + 1];
        diffs[p] = f[i] - f[i + 1];
    });
    const T drho = tree_sum<(Q + 1) / 2>(sums);
    const T jx = axis_sum<0>(diffs), jy = axis_sum<1>(diffs), jz = axis_sum<2>(diffs);
    const T rho = T(1) + drho, inv = T(1) / rho;
    T ux, uy, uz, fx, fy, fz;
    if constexpr (S == Solid::drag) {
        // F_h = λ (j − ρ v_p) = λ ρ (u_f − v_p); the cell's force density F = ρ a − F_h
        drag->hx = drag->weight * (jx - rho * drag->vx);
        drag->hy = drag->weight * (jy - rho * drag->vy);
        drag->hz = drag->weight * (jz - rho * drag->vz);
        fx = rho * r.ax - drag->hx;
        fy = rho * r.ay - drag->hy;
        fz = rho * r.az - drag->hz;
        ux = (jx + T(0.5) * fx) * inv;  // u = (j + F/2)/ρ
        uy = (jy + T(0.5) * fy) * inv;
        uz = (jz + T(0.5) * fz) * inv;
    } else {
        ux = jx * inv + T(0.5) * r.ax;  // u = (j + F/2)/ρ
        uy = jy * inv + T(0.5) * r.ay;
        uz = jz * inv + T(0.5) * r.az;
        fx = rho * r.ax;
        fy = rho * r.ay;
        fz = rho * r.az;
    }
    const T uf = ux * fx + uy * fy + uz * fz;
    // f^eq_i − w_i = w_i (base + 4.5 ρ cu²) ± w_i 3 ρ cu for the pair (i, ī), cu = c_i·u
    const T base = drho - T(1.5) * rho * (ux * ux + uy * uy + uz * uz);
    const T rho3 = T(3) * rho, rho45 = T(4.5) * rho;
    T omega = r.omega;
    if constexpr (Bingham || Les) {
        // S_ab = −3/(2ρτ) [Σ c_a c_b (f − f^eq) + ½ (F_a u_b + u_a F_b)] (Krüger et al. 2009, Eq. 45);
        // c_a c_b is the same for i and ī, so only the pair's sum f_i + f_ī − 2 (even part) enters
        T pxx = 0, pyy = 0, pzz = 0, pxy = 0, pxz = 0, pyz = 0;
        for_each_pair([&](auto p) SABO_ALWAYS_INLINE {
            constexpr int i = 2 * p + 1;
            constexpr T w = static_cast<T>(weight[i]);
            const T cu = project<i>(ux, uy, uz);
            const T d = f[i] + f[i + 1] - T(2) * w * (base + rho45 * cu * cu);
            if constexpr (cx[i] != 0) pxx += d;
            if constexpr (cy[i] != 0) pyy += d;
            if constexpr (cz[i] != 0) pzz += d;
            if constexpr (cx[i] * cy[i] != 0) pxy += cx[i] * cy[i] > 0 ? d : -d;
            if constexpr (cx[i] * cz[i] != 0) pxz += cx[i] * cz[i] > 0 ? d : -d;
            if constexpr (cy[i] * cz[i] != 0) pyz += cy[i] * cz[i] > 0 ? d : -d;
        });
        const T sxx = pxx + fx * ux, syy = pyy + fy * uy, szz = pzz + fz * uz;
        const T sxy = pxy + T(0.5) * (fx * uy + ux * fy);
        const T sxz = pxz + T(0.5) * (fx * uz + ux * fz);
        const T syz = pyz + T(0.5) * (fy * uz + uy * fz);
        const T ss = sxx * sxx + syy * syy + szz * szz + T(2) * (sxy * sxy + sxz * sxz + syz * syz);
        T t = r.tau;
        clamped = 0;
        if constexpr (Bingham) {
            // γ̇ = 1.5/(ρτ) sqrt(2 Π:Π); ν_app = ν_p + τ0/γ̇, τ = ½ + 3 ν_app; γ̇ = 0 ↦ τ_max
            // (written branch-free, every operation on every lane: the vectoriser does not speculate
            // a division behind a condition)
            // (3 τ0/γ̇ = 2 τ0 ρ τ / sqrt(2 Π:Π): one division fewer on the loop's critical path)
            const T root = std::sqrt(T(2) * ss);
            const bool flowing = root > T(0);
            const T plastic =
                T(0.5) + T(3) * r.nu_plastic + T(2) * r.yield * rho * tau / (flowing ? root : T(1));
            t = flowing ? plastic : r.tau_max;
            clamped = static_cast<C>(static_cast<C>(t >= r.tau_max) - static_cast<C>(t < r.tau_min));
            t = std::min(std::max(t, r.tau_min), r.tau_max);
        }
        // Smagorinsky (an option beyond the reference model): ν_t = (C Δx)² |S| solved with |S| from the same
        // moments, τ = ½ (τ0 + sqrt(τ0² + 18 √2 C² |Π| / ρ)) (Hou et al. 1996)
        if constexpr (Les)
            t = T(0.5) * (t + std::sqrt(t * t + T(18) * std::numbers::sqrt2_v<T> * r.smagorinsky *
                                                    r.smagorinsky * std::sqrt(ss) / rho));
        tau = t;
        omega = T(1) / t;
    }
    // Guo term w_i (1 − ω/2) [3 (c_i·F − u·F) + 9 (c_i·u)(c_i·F)]: even part 9 cu cf − 3 u·F, odd 3 cf.
    // With the equilibrium's even part w_i (base + 4.5 ρ cu²) and odd part ±3 w_i ρ cu, the pair (i, ī)
    // becomes f ← (1 − ω) f + a ± b, a = w_i [c0 + cu (k1 cu + k2 cf)], b = w_i (k3 cu + k4 cf), the
    // constants multiplied by the two weights of the pairs once per cell (fewer operations on the
    // vector loop's critical path than the textbook form).
    const T g = T(1) - T(0.5) * omega, keep = T(1) - omega;
    const T c0 = omega * base - T(3) * g * uf;
    const T k1 = omega * rho45, k2 = T(9) * g, k3 = omega * rho3, k4 = T(3) * g;
    constexpr T w_face = static_cast<T>(weight[1]), w_edge = static_cast<T>(weight[7]);
    const T face[5] = {w_face * c0, w_face * k1, w_face * k2, w_face * k3, w_face * k4};
    const T edge[5] = {w_edge * c0, w_edge * k1, w_edge * k2, w_edge * k3, w_edge * k4};
    if constexpr (S == Solid::psm) {
        // the partially saturated share, from the populations before the collision: per pair, the
        // non-equilibria toward u (n) and toward v_p (m) of f_i and f_ī; equilibria as deviations from w_i
        const T bw = drag->weight, vx = drag->vx, vy = drag->vy, vz = drag->vz;
        const T base_v = drho - T(1.5) * rho * (vx * vx + vy * vy + vz * vz);
        constexpr T w0 = static_cast<T>(weight[0]);
        T hx = 0, hy = 0, hz = 0;
        // rest population: Ω^s_0 = f_0^eq(v_p) − f_0^eq(u), no momentum
        const T n0 = f[0] - w0 * base;
        const T g3 = T(3) * g, g9 = T(9) * g, g3uf = g3 * uf;
        f[0] = keep * f[0] + w0 * c0 + bw * (omega * n0 + w0 * (base_v - base) + w0 * g3uf);
        for_each_pair([&](auto p) SABO_ALWAYS_INLINE {
            constexpr int i = 2 * p + 1;
            constexpr T w = static_cast<T>(weight[i]);
            const T(&k)[5] = weight[i] == weight[1] ? face : edge;
            const T cu = project<i>(ux, uy, uz);
            const T cv = project<i>(vx, vy, vz);
            const T cf = project<i>(fx, fy, fz);
            const T eu = w * (base + rho45 * cu * cu), ou = w * rho3 * cu;  // f^eq(u): eu ± ou
            const T ev = w * (base_v + rho45 * cv * cv), ov = w * rho3 * cv;
            const T n_i = f[i] - (eu + ou), n_o = f[i + 1] - (eu - ou);
            const T s_i = n_o - (f[i] - (ev + ov)), s_o = n_i - (f[i + 1] - (ev - ov));  // Ω^s
            const T a = k[0] + cu * (k[1] * cu + k[2] * cf);
            const T b = k[3] * cu + k[4] * cf;
            const T ge = w * (g9 * cu * cf - g3uf), go = w * g3 * cf;  // Guo term: ge ± go
            f[i] = keep * f[i] + (a + b) + bw * (omega * n_i + s_i - (ge + go));
            f[i + 1] = keep * f[i + 1] + (a - b) + bw * (omega * n_o + s_o - (ge - go));
            // F_h = −B λ Σ c_i Ω^s_i: the pair adds −B λ c_i (Ω^s_i − Ω^s_ī)
            const T d = s_o - s_i;
            if constexpr (cx[i] != 0) hx += cx[i] > 0 ? d : -d;
            if constexpr (cy[i] != 0) hy += cy[i] > 0 ? d : -d;
            if constexpr (cz[i] != 0) hz += cz[i] > 0 ? d : -d;
        });
        drag->hx = bw * hx;
        drag->hy = bw * hy;
        drag->hz = bw * hz;
        return;
    }
    f[0] = keep * f[0] + static_cast<T>(weight[0]) * c0;
    for_each_pair([&](auto p) SABO_ALWAYS_INLINE {
        constexpr int i = 2 * p + 1;
        static_assert(weight[i] == weight[1] || weight[i] == weight[7]);
        const T(&k)[5] = weight[i] == weight[1] ? face : edge;
        const T cu = project<i>(ux, uy, uz);
        const T cf = project<i>(fx, fy, fz);
        const T a = k[0] + cu * (k[1] * cu + k[2] * cf);
        const T b = k[3] * cu + k[4] * cf;
        f[i] = keep * f[i] + (a + b);
        f[i + 1] = keep * f[i + 1] + (a - b);
    });
}

// The widest vector the build targets (the sweep asks GCC for 512-bit vectors where there are any) and the
// values of T it holds
#if defined(__AVX512F__)
inline constexpr std::size_t simd_bytes = 64;
#elif defined(__AVX__)
inline constexpr std::size_t simd_bytes = 32;
#else
inline constexpr std::size_t simd_bytes = 16;
#endif
template <class T>
inline constexpr std::size_t simd_lanes = simd_bytes / sizeof(T);

// Cells gathered one by one (next to walls, on the free surface), collided together: population i
// of lane l at f[i][l], full populations (not deviations).
constexpr int lanes = 16;

struct Batch {
    double f[Q][lanes];
    double tau[lanes];  // in: τ of the previous step; out: the new τ
    // cells covered by a grain: the entry in the lattice's grain-cell list (−1: none), the grain's surface
    // velocity and the coupling weight (in), the hydrodynamic force (out); see SolidDrag
    int grain[lanes];
    double grain_v[3][lanes];
    double grain_weight[lanes];
    double hydro[3][lanes];
    int clamped[lanes];
    std::size_t k[lanes];   // where each lane came from
    double counted[lanes];  // 1 for a cell whose force on the obstacles counts (an own plane's), else 0
    // each lane's neighbour along c_i: its index, or for a solid one −1 − its obstacle element (element 0:
    // a wall beyond the domain's edge)
    std::ptrdiff_t nb[lanes][Q];
    int surface[lanes];  // interface cells: index in the interface list; −1 otherwise
    double rho[lanes];   // interface cells: density of the gathered populations
    int count = 0;
    Batch() {  // every lane starts as a fluid cell at rest
        for (int i = 0; i < Q; ++i)
            for (int l = 0; l < lanes; ++l) f[i][l] = weight[i];
        for (int l = 0; l < lanes; ++l) {
            tau[l] = 1.0;
            clamped[l] = 0;
            grain[l] = -1;
            grain_weight[l] = 0.0;
            grain_v[0][l] = grain_v[1][l] = grain_v[2][l] = 0.0;
        }
    }
};

// S other than none: some lanes are covered by grains (the others have weight 0 and exchange nothing).
template <bool Bingham, bool Les, Solid S>
inline void collide_batch(Batch& b, const Relaxation<double>& r) {
#pragma omp simd
    for (int l = 0; l < b.count; ++l) {
        double f[Q];
#pragma GCC unroll 19
        for (int i = 0; i < Q; ++i) f[i] = b.f[i][l] - weight[i];
        if constexpr (S != Solid::none) {
            SolidDrag<double> drag{b.grain_v[0][l], b.grain_v[1][l], b.grain_v[2][l], b.grain_weight[l]};
            collide_cell<Bingham, Les, S>(f, b.tau[l], b.clamped[l], r, &drag);
            b.hydro[0][l] = drag.hx;
            b.hydro[1][l] = drag.hy;
            b.hydro[2][l] = drag.hz;
        } else {
            collide_cell<Bingham, Les>(f, b.tau[l], b.clamped[l], r);
        }
#pragma GCC unroll 19
        for (int i = 0; i < Q; ++i) b.f[i][l] = f[i] + weight[i];
    }
}

// Momentum the fluid gives an obstacle through link i (population f_i* leaving toward it), with the
// returning population f_i* − 6 w_i c_i·u_w (moving-wall bounce-back, reference density 1).
[[nodiscard]] inline double returned(double post, int i, const Vec3& uw) {
    return post - 6.0 * weight[i] * (cx[i] * uw.x + cy[i] * uw.y + cz[i] * uw.z);
}

// Equilibrium population i for density rho and velocity u.
[[nodiscard]] inline double equilibrium(int i, double rho, const Vec3& u) {
    const double cu = cx[i] * u.x + cy[i] * u.y + cz[i] * u.z;
    return weight[i] * rho * (1.0 + 3.0 * cu + 4.5 * cu * cu - 1.5 * norm2(u));
}

}  // namespace sabo::lbm::detail
