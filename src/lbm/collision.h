// SPDX-License-Identifier: MIT
// Internal to the lattice: the batched BGK–Guo collision and the moving-wall bounce-back term, shared
// by the bulk sweep (fluid_lattice.cpp) and the free surface (free_surface.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "core/vec3.h"
#include "lbm/d3q19.h"
#include "lbm/rheology.h"

namespace sabo::lbm::detail {

// Lanes of one batch: up to `lanes` cells collide together, each population i of the batch a
// contiguous row f[i][0..n) (the compiler vectorises every loop over the lanes).
constexpr int lanes = 16;
struct Batch {
    double f[Q][lanes];
    double tau[lanes];  // in: τ of the previous step; out: the new τ
    int clamped[lanes];
    // cells of a batch gathered one by one (next to walls): where each lane came from
    int x[lanes], y[lanes];
    std::size_t k[lanes];
    int surface[lanes];  // interface cells: index in the interface list; −1 otherwise
    double rho[lanes];   // interface cells: density of the gathered populations
    int count = 0;
    Batch() {  // every lane starts as a fluid cell at rest
        for (int i = 0; i < Q; ++i)
            for (int l = 0; l < lanes; ++l) f[i][l] = weight[i];
        for (int l = 0; l < lanes; ++l) tau[l] = 1.0;
    }
};

// BGK collision with Guo forcing of the batch (in place), force density F = ρ a. Bingham:
// τ from the strain rate of the non-equilibrium moments, with the previous τ in S_ab (SPEC §2.1).
[[gnu::always_inline]] inline void collide(Batch& b, int used, const Vec3& accel, const Rheology& rh) {
    // whole groups of 4 lanes (unused ones hold finite stale cells): the vector loops need no remainder
    const int n = std::min(lanes, (used + 3) / 4 * 4);
    // every loop runs over the lanes innermost (contiguous, vectorised); sums over i in ascending order
    double rho[lanes], ux[lanes], uy[lanes], uz[lanes], omega[lanes];
#pragma omp simd
    for (int l = 0; l < n; ++l) rho[l] = ux[l] = uy[l] = uz[l] = 0.0;
#pragma GCC unroll 19
    for (int i = 0; i < Q; ++i) {
        const double ci[3] = {static_cast<double>(cx[i]), static_cast<double>(cy[i]),
                              static_cast<double>(cz[i])};
#pragma omp simd
        for (int l = 0; l < n; ++l) {
            const double fi = b.f[i][l];
            rho[l] += fi;
            ux[l] += ci[0] * fi;
            uy[l] += ci[1] * fi;
            uz[l] += ci[2] * fi;
        }
    }
    // per lane, once: f^eq_i = w_i (A + cu (B + C cu)) with A = ρ(1 − 1.5 u·u), B = 3ρ, C = 4.5ρ (used by
    // the strain rate and the relaxation alike), F = ρ a and u·F for the Guo term
    double A[lanes], B[lanes], C[lanes], uF[lanes], fx[lanes], fy[lanes], fz[lanes], G[lanes];
    const double tau_newtonian = rh.tau;
#pragma omp simd
    for (int l = 0; l < n; ++l) {
        const double r = rho[l], inv = 1.0 / r;
        const double vx = (ux[l] + 0.5 * r * accel.x) * inv;  // u = (Σ f c + F/2)/ρ
        const double vy = (uy[l] + 0.5 * r * accel.y) * inv;
        const double vz = (uz[l] + 0.5 * r * accel.z) * inv;
        ux[l] = vx;
        uy[l] = vy;
        uz[l] = vz;
        A[l] = r * (1.0 - 1.5 * (vx * vx + vy * vy + vz * vz));
        B[l] = 3.0 * r;
        C[l] = 4.5 * r;
        fx[l] = r * accel.x;
        fy[l] = r * accel.y;
        fz[l] = r * accel.z;
        uF[l] = vx * fx[l] + vy * fy[l] + vz * fz[l];
        omega[l] = 1.0 / tau_newtonian;
    }
    if (rh.bingham || rh.smagorinsky > 0.0) {
        // S_ab = −3/(2ρτ) [Σ c_a c_b (f − f^eq) + ½ (F_a u_b + u_a F_b)] (Krüger et al. 2009, Eq. 45)
        double pxx[lanes], pyy[lanes], pzz[lanes], pxy[lanes], pxz[lanes], pyz[lanes];
#pragma omp simd
        for (int l = 0; l < n; ++l) pxx[l] = pyy[l] = pzz[l] = pxy[l] = pxz[l] = pyz[l] = 0.0;
        for (int i = 0; i < Q; ++i) {
            const double w = weight[i];
            const double ci[3] = {static_cast<double>(cx[i]), static_cast<double>(cy[i]),
                                  static_cast<double>(cz[i])};
#pragma omp simd
            for (int l = 0; l < n; ++l) {
                const double cu = ci[0] * ux[l] + ci[1] * uy[l] + ci[2] * uz[l];
                const double d = b.f[i][l] - w * (A[l] + cu * (B[l] + C[l] * cu));
                pxx[l] += ci[0] * ci[0] * d;
                pyy[l] += ci[1] * ci[1] * d;
                pzz[l] += ci[2] * ci[2] * d;
                pxy[l] += ci[0] * ci[1] * d;
                pxz[l] += ci[0] * ci[2] * d;
                pyz[l] += ci[1] * ci[2] * d;
            }
        }
#pragma omp simd
        for (int l = 0; l < n; ++l) {
            const double r = rho[l], vx = ux[l], vy = uy[l], vz = uz[l];
            const double sxx = pxx[l] + fx[l] * vx, syy = pyy[l] + fy[l] * vy, szz = pzz[l] + fz[l] * vz;
            const double sxy = pxy[l] + 0.5 * (fx[l] * vy + vx * fy[l]);
            const double sxz = pxz[l] + 0.5 * (fx[l] * vz + vx * fz[l]);
            const double syz = pyz[l] + 0.5 * (fy[l] * vz + vy * fz[l]);
            const double ss = sxx * sxx + syy * syy + szz * szz + 2.0 * (sxy * sxy + sxz * sxz + syz * syz);
            double tau = rh.tau;
            if (rh.bingham) tau = rh.bingham_tau(1.5 / (r * b.tau[l]) * std::sqrt(2.0 * ss), b.clamped[l]);
            // Smagorinsky (option, not SPEC): ν_t = (C Δx)² |S| solved with |S| from the same moments,
            // τ = ½ (τ0 + sqrt(τ0² + 18 √2 C² |Π| / ρ)) (Hou et al. 1996)
            if (rh.smagorinsky > 0.0)
                tau = 0.5 * (tau + std::sqrt(tau * tau + 18.0 * std::numbers::sqrt2 * rh.smagorinsky *
                                                             rh.smagorinsky * std::sqrt(ss) / r));
            b.tau[l] = tau;
            omega[l] = 1.0 / tau;
        }
    }
    // the Guo term w_i (1 − ω/2) [3 (c_i·F − u·F) + 9 (c_i·u)(c_i·F)] with the final ω
#pragma omp simd
    for (int l = 0; l < n; ++l) G[l] = 1.0 - 0.5 * omega[l];
        // unrolled: the components of c_i are the constants 0 and ±1, so most products vanish
#pragma GCC unroll 19
    for (int i = 0; i < Q; ++i) {
        const double w = weight[i];
        const double ci[3] = {static_cast<double>(cx[i]), static_cast<double>(cy[i]),
                              static_cast<double>(cz[i])};
#pragma omp simd
        for (int l = 0; l < n; ++l) {
            const double cu = ci[0] * ux[l] + ci[1] * uy[l] + ci[2] * uz[l];
            const double feq = w * (A[l] + cu * (B[l] + C[l] * cu));
            const double cf = ci[0] * fx[l] + ci[1] * fy[l] + ci[2] * fz[l];
            const double guo = w * G[l] * (3.0 * (cf - uF[l]) + 9.0 * cu * cf);
            const double fi = b.f[i][l];
            b.f[i][l] = fi - omega[l] * (fi - feq) + guo;
        }
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
