// SPDX-License-Identifier: MIT
// The lattice's stream–collide on an OpenCL device (docs/lbm.md, "Backends"): the CPU lattice's numerics
// (src/lbm/collision.h, fluid_lattice.cpp) for fluid cells, one work-item per stored cell, the populations
// in the CPU lattice's layout (population i of cell k at f[i·SLOT + k], stored as f_i − w_i; the AA pattern:
// an even step reads and writes a cell's own slots, an odd step reads the neighbours' and writes into them).
// Specialised when built (OpenClLattice passes them): REAL (float | double, storage and arithmetic), ACC
// (the type of the momentum sums), BINGHAM, LES, FREE_SURFACE, the shape NX NY NZ ROW PLANE SLOT CELLS,
// periodic axes PX PY PZ, the rheology's constants, and for a slab of a run divided among MPI ranks
// (DIVIDED 1) its own planes [OWN_BEGIN, OWN_END) (0 and NX when whole). Nothing here adds floating-point
// numbers in an order that depends on the scheduling: each cell writes its own slots and its own wall links' momenta; sums over cells are made by
// reduce_link_chunks() and sum_element_chunks() in a fixed order.
#if defined(REAL_IS_DOUBLE) || defined(ACC_IS_DOUBLE)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif

typedef REAL real;
typedef ACC acc;

#define Q 19
constant int CX[Q] = {0, 1, -1, 0, 0, 0, 0, 1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0};
constant int CY[Q] = {0, 0, 0, 1, -1, 0, 0, 1, -1, -1, 1, 0, 0, 0, 0, 1, -1, 1, -1};
constant int CZ[Q] = {0, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, 1, -1, -1, 1, 1, -1, -1, 1};
#define W0 ((real)(1.0 / 3.0))
#define W_FACE ((real)(1.0 / 18.0))
#define W_EDGE ((real)(1.0 / 36.0))
#define WEIGHT(i) ((i) == 0 ? W0 : ((i) < 7 ? W_FACE : W_EDGE))
#define OPPOSITE(i) ((i) == 0 ? 0 : ((i) % 2 == 1 ? (i) + 1 : (i) - 1))

#define FLUID 0
#define INTERFACE 1
#define GAS 2
#define OBSTACLE 3

// The neighbour of (x, y, z) along c_i (sign +1) or −c_i (−1): its stored index, or −1 beyond a closed edge.
inline long neighbour(int x, int y, int z, int i, int sign) {
    int px = x + sign * CX[i], py = y + sign * CY[i], pz = z + sign * CZ[i];
    if (px < 0 || px >= NX) {
        if (!PX) return -1;
        px = (px + NX) % NX;
    }
    if (py < 0 || py >= NY) {
        if (!PY) return -1;
        py = (py + NY) % NY;
    }
    if (pz < 0 || pz >= NZ) {
        if (!PZ) return -1;
        pz = (pz + NZ) % NZ;
    }
    return (long)px + (long)ROW * py + (long)PLANE * pz;
}

// The element of the solid neighbour n (an obstacle cell's, or 0: a wall beyond the domain's edge).
inline int element_of(long n, global const uchar* type, global const ushort* element) {
    return n < 0 ? 0 : (type[n] == OBSTACLE ? (int)element[n] : 0);
}

// c_i · u_e of element e's wall velocity
inline real wall_term(int i, int e, global const real* wall_u) {
    return (real)6 * WEIGHT(i) *
           ((real)CX[i] * wall_u[3 * e] + (real)CY[i] * wall_u[3 * e + 1] + (real)CZ[i] * wall_u[3 * e + 2]);
}

// A cell covered by a moving solid (a grain of the coupling; collision.h's SolidDrag): in, the weight B λ and
// the solid's velocity at the cell's centre; out, the force F_h on the solid.
typedef struct {
    real w, vx, vy, vz;
    real hx, hy, hz;
} SolidDrag;

// BGK collision with Guo forcing of one cell in place (collision.h's collide_cell): f as deviations from
// rest; τ in: the previous step's, out: the new one (Bingham, Smagorinsky); clamped −1/0/+1. `solid` (built
// with SOLID 1, the drag, or 2, the partially saturated collision; null for a cell no solid covers): the
// exchange with the solid covering the cell.
inline void collide(real* f, real* tau_io, int* clamped, real ax, real ay, real az, SolidDrag* solid) {
    real drho = f[0], jx = 0, jy = 0, jz = 0;
#pragma unroll
    for (int i = 1; i < Q; ++i) {
        drho += f[i];
        jx += (real)CX[i] * f[i];
        jy += (real)CY[i] * f[i];
        jz += (real)CZ[i] * f[i];
    }
    const real rho = (real)1 + drho, inv = (real)1 / rho;
    real ux = jx * inv + (real)0.5 * ax, uy = jy * inv + (real)0.5 * ay, uz = jz * inv + (real)0.5 * az;
    real fx = rho * ax, fy = rho * ay, fz = rho * az;
    if (SOLID == 1 && solid) {
        // F_h = B λ (j − ρ v_p); the cell's force density F = ρ a − F_h, u = (j + F/2)/ρ
        solid->hx = solid->w * (jx - rho * solid->vx);
        solid->hy = solid->w * (jy - rho * solid->vy);
        solid->hz = solid->w * (jz - rho * solid->vz);
        fx -= solid->hx;
        fy -= solid->hy;
        fz -= solid->hz;
        ux = (jx + (real)0.5 * fx) * inv;
        uy = (jy + (real)0.5 * fy) * inv;
        uz = (jz + (real)0.5 * fz) * inv;
    }
    const real uf = ux * fx + uy * fy + uz * fz;
    const real base = drho - (real)1.5 * rho * (ux * ux + uy * uy + uz * uz);
    const real rho45 = (real)4.5 * rho;
    real omega = (real)OMEGA;
    *clamped = 0;
#if BINGHAM || LES
    // S_ab from the non-equilibrium moments (Krüger et al. 2009, Eq. 45), pairs' even parts only
    real pxx = 0, pyy = 0, pzz = 0, pxy = 0, pxz = 0, pyz = 0;
#pragma unroll
    for (int i = 1; i < Q; i += 2) {
        const real cu = (real)CX[i] * ux + (real)CY[i] * uy + (real)CZ[i] * uz;
        const real d = f[i] + f[i + 1] - (real)2 * WEIGHT(i) * (base + rho45 * cu * cu);
        pxx += (real)(CX[i] * CX[i]) * d;
        pyy += (real)(CY[i] * CY[i]) * d;
        pzz += (real)(CZ[i] * CZ[i]) * d;
        pxy += (real)(CX[i] * CY[i]) * d;
        pxz += (real)(CX[i] * CZ[i]) * d;
        pyz += (real)(CY[i] * CZ[i]) * d;
    }
    const real sxx = pxx + fx * ux, syy = pyy + fy * uy, szz = pzz + fz * uz;
    const real sxy = pxy + (real)0.5 * (fx * uy + ux * fy);
    const real sxz = pxz + (real)0.5 * (fx * uz + ux * fz);
    const real syz = pyz + (real)0.5 * (fy * uz + uy * fz);
    const real ss = sxx * sxx + syy * syy + szz * szz + (real)2 * (sxy * sxy + sxz * sxz + syz * syz);
    real t = (real)TAU;
#if BINGHAM
    // ν_app = ν_p + τ0/γ̇, γ̇ = 1.5/(ρτ) sqrt(2 Π:Π) with the previous τ; γ̇ = 0 ↦ τ_max; clamped
    const real root = sqrt((real)2 * ss);
    t = root > (real)0 ? (real)0.5 + (real)3 * (real)NU_PLASTIC + (real)2 * (real)YIELD * rho * *tau_io / root
                       : (real)TAU_MAX;
    *clamped = (t >= (real)TAU_MAX ? 1 : 0) - (t < (real)TAU_MIN ? 1 : 0);
    t = fmin(fmax(t, (real)TAU_MIN), (real)TAU_MAX);
#endif
#if LES
    t = (real)0.5 * (t + sqrt(t * t + (real)18 * sqrt((real)2) * (real)SMAGORINSKY * (real)SMAGORINSKY *
                                          sqrt(ss) / rho));
#endif
    *tau_io = t;
    omega = (real)1 / t;
#endif
    // f_i ← (1 − ω) f_i + a ± b per pair (collision.h): a = w (ω base − 3 g u·F + ω 4.5 ρ cu² + 9 g cu cf),
    // b = w (3 ω ρ cu + 3 g cf), g = 1 − ω/2
    const real g = (real)1 - (real)0.5 * omega, keep = (real)1 - omega;
    const real c0 = omega * base - (real)3 * g * uf;
    const real k1 = omega * rho45, k2 = (real)9 * g, k3 = omega * (real)3 * rho, k4 = (real)3 * g;
    if (SOLID == 2 && solid) {
        // the partially saturated share β = B λ (collision.h): per pair, the non-equilibria toward u (n) and
        // toward v_p (Ω^s, the non-equilibrium bounce-back); F_h = −β Σ c_i Ω^s_i
        const real bw = solid->w, vx = solid->vx, vy = solid->vy, vz = solid->vz;
        const real base_v = drho - (real)1.5 * rho * (vx * vx + vy * vy + vz * vz);
        const real rho3 = (real)3 * rho, g3 = (real)3 * g, g9 = (real)9 * g, g3uf = g3 * uf;
        const real n0 = f[0] - W0 * base;
        f[0] = keep * f[0] + W0 * c0 + bw * (omega * n0 + W0 * (base_v - base) + W0 * g3uf);
        real hx = 0, hy = 0, hz = 0;
#pragma unroll
        for (int i = 1; i < Q; i += 2) {
            const real w = WEIGHT(i);
            const real cu = (real)CX[i] * ux + (real)CY[i] * uy + (real)CZ[i] * uz;
            const real cv = (real)CX[i] * vx + (real)CY[i] * vy + (real)CZ[i] * vz;
            const real cf = (real)CX[i] * fx + (real)CY[i] * fy + (real)CZ[i] * fz;
            const real eu = w * (base + rho45 * cu * cu), ou = w * rho3 * cu;
            const real ev = w * (base_v + rho45 * cv * cv), ov = w * rho3 * cv;
            const real n_i = f[i] - (eu + ou), n_o = f[i + 1] - (eu - ou);
            const real s_i = n_o - (f[i] - (ev + ov)), s_o = n_i - (f[i + 1] - (ev - ov));
            const real a = w * c0 + cu * (w * k1 * cu + w * k2 * cf);
            const real b = w * k3 * cu + w * k4 * cf;
            const real ge = w * (g9 * cu * cf - g3uf), go = w * g3 * cf;
            f[i] = keep * f[i] + (a + b) + bw * (omega * n_i + s_i - (ge + go));
            f[i + 1] = keep * f[i + 1] + (a - b) + bw * (omega * n_o + s_o - (ge - go));
            const real d = s_o - s_i;
            hx += (real)CX[i] * d;
            hy += (real)CY[i] * d;
            hz += (real)CZ[i] * d;
        }
        solid->hx = bw * hx;
        solid->hy = bw * hy;
        solid->hz = bw * hz;
        return;
    }
    f[0] = keep * f[0] + W0 * c0;
#pragma unroll
    for (int i = 1; i < Q; i += 2) {
        const real w = WEIGHT(i);
        const real cu = (real)CX[i] * ux + (real)CY[i] * uy + (real)CZ[i] * uz;
        const real cf = (real)CX[i] * fx + (real)CY[i] * fy + (real)CZ[i] * fz;
        const real a = w * c0 + cu * (w * k1 * cu + w * k2 * cf);
        const real b = w * k3 * cu + w * k4 * cf;
        f[i] = keep * f[i] + (a + b);
        f[i + 1] = keep * f[i + 1] + (a - b);
    }
}

// The populations of cell k before its collision, as deviations from rest, at the parity `odd` of the
// step about to run (the CPU's gather): an even step's are in the cell's own slots; an odd step's f_i
// arrives from x − c_i, where the even step stored it in slot ī, and from a solid it is this cell's own
// f_ī* (kept in slot i) returned with the wall's term.
inline void gather(const int odd, int x, int y, int z, long k, uint lk, global const real* f,
                   global const uchar* type, global const ushort* element, global const real* wall_u, real* fl) {
    if (!odd) {
#pragma unroll
        for (int i = 0; i < Q; ++i) fl[i] = f[i * (long)SLOT + k];
        return;
    }
#pragma unroll
    for (int i = 0; i < Q; ++i) {
        const int o = OPPOSITE(i);
        if ((lk >> o) & 1u) {
            const int e = element_of(neighbour(x, y, z, o, 1), type, element);
            fl[i] = f[i * (long)SLOT + k] - wall_term(o, e, wall_u);
        } else {
            fl[i] = f[o * (long)SLOT + neighbour(x, y, z, i, -1)];
        }
    }
}

// ρ and u = (j + F/2)/ρ of fluid cell k from its incoming populations (what the snapshot, the summaries and
// the surface's demotions read)
inline void fluid_moments(const int odd, int x, int y, int z, long k, global const real* f, global const uchar* type,
                          global const uint* links, global const ushort* element, global const real* wall_u,
                          real ax, real ay, real az, acc* rho, real* u) {
    real fl[Q];
    gather(odd, x, y, z, k, links[k], f, type, element, wall_u, fl);
    acc r = 0;
    real jx = 0, jy = 0, jz = 0;
    for (int i = 0; i < Q; ++i) {
        r += (acc)fl[i];
        jx += (real)CX[i] * fl[i];
        jy += (real)CY[i] * fl[i];
        jz += (real)CZ[i] * fl[i];
    }
    r += (acc)1;
    *rho = r;
    u[0] = jx / (real)r + (real)0.5 * ax;
    u[1] = jy / (real)r + (real)0.5 * ay;
    u[2] = jz / (real)r + (real)0.5 * az;
}

#if FREE_SURFACE
// An interface cell's populations from the gas and from the gas side (against the surface normal n)
// replaced by the atmospheric reconstruction (the CPU's reconstruct()): f_j = f_j^eq(ρ_A, u) + f_j̄^eq(ρ_A, u)
// − f_j̄*, with u the cell's last collision velocity and f_j̄* what it sent toward there in the last step;
// as deviations from rest, 2 w_j (4.5 (c_j·u)² − 1.5 u²) − (f_j̄* − w_j). A direction tangential to a flat
// surface must not flip on the round-off of n (the threshold).
inline void reconstruct(int x, int y, int z, long k, uint lk, global const uchar* type, global const real* su,
                        global const real* normal, global const real* out, real* fl) {
    const real ux = su[3 * k], uy = su[3 * k + 1], uz = su[3 * k + 2];
    const real nx = normal[3 * k], ny = normal[3 * k + 1], nz = normal[3 * k + 2];
    const real tangential = (real)1e-9 * (fabs(nx) + fabs(ny) + fabs(nz));
    const real u2 = (real)1.5 * (ux * ux + uy * uy + uz * uz);
#pragma unroll
    for (int j = 1; j < Q; ++j) {
        const int o = OPPOSITE(j);
        if ((lk >> o) & 1u) continue;  // from a solid: bounced back
        const long src = neighbour(x, y, z, j, -1);
        const int from_gas = type[src] == GAS;
        const int gas_side = nx * (real)CX[j] + ny * (real)CY[j] + nz * (real)CZ[j] < -tangential;
        if (!from_gas && !gas_side) continue;
        const real cu = (real)CX[j] * ux + (real)CY[j] * uy + (real)CZ[j] * uz;
        fl[j] = (real)2 * WEIGHT(j) * ((real)4.5 * cu * cu - u2) - out[o * (long)CELLS + k];
    }
}
#define SURFACE_PARAMS , global real *su, global const real *normal, global real *out, global acc *srho, global uchar *out_known
#define SURFACE_ARGS , su, normal, out, srho, out_known
#else
#define SURFACE_PARAMS
#define SURFACE_ARGS
#endif
// the cells a moving solid covers (its share ε of the cell, 0: none; its velocity there) and the force on it
#if SOLID && FREE_SURFACE
#define SOLID_PARAMS , global const real *solid_fraction, global const real *solid_v, global acc *solid_force, global const real *fill
#define SOLID_ARGS , solid_fraction, solid_v, solid_force, fill
#elif SOLID
#define SOLID_PARAMS , global const real *solid_fraction, global const real *solid_v, global acc *solid_force
#define SOLID_ARGS , solid_fraction, solid_v, solid_force
#else
#define SOLID_PARAMS
#define SOLID_ARGS
#endif

// One step of fluid or interface cell (x, y, z). links: bit i set where the neighbour along c_i is solid;
// link_start: the cell's first entry in link_momentum (its links in ascending direction).
inline void step_cell(const int odd, global real* f, global real* tau, global const uchar* type,
                      global const uint* links, global const ushort* element, global const real* wall_u,
                      global const uint* link_start, global acc* link_momentum, local uint* counts, real ax,
                      real ay, real az SURFACE_PARAMS SOLID_PARAMS) {
    const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
    if (x >= NX) return;
    const long k = (long)x + (long)ROW * y + (long)PLANE * z;
    const uchar t_k = type[k];
    if (t_k != FLUID && (!FREE_SURFACE || t_k != INTERFACE)) {
#if FREE_SURFACE
        // a gas cell next to a wall (wet in other steps) gives the walls nothing this step
        if (t_k == GAS && links[k] != 0u) {
            const uint first = link_start[k], count = popcount(links[k]);
            for (uint j = 0; j < count; ++j) link_momentum[first + j] = 0;
        }
#endif
#if SOLID
        // nor does a dry cell give its solid anything
        if (solid_fraction[k] > (real)0) solid_force[3 * k] = solid_force[3 * k + 1] = solid_force[3 * k + 2] = 0;
#endif
        return;
    }
    atomic_inc(&counts[2]);
    const uint lk = links[k];
    real fl[Q];
    gather(odd, x, y, z, k, lk, f, type, element, wall_u, fl);
#if FREE_SURFACE
    acc rho_surface = 0;
    if (t_k == INTERFACE) {
        reconstruct(x, y, z, k, lk, type, su, normal, out, fl);
        for (int i = 0; i < Q; ++i) rho_surface += (acc)fl[i];
        rho_surface += (acc)1;
    }
#endif
    real t = BINGHAM ? tau[k] : (real)TAU;
    int clamped = 0;
    // the cell's force density besides the weighed share of gravity's (−F_h of a covered cell); a
    // partially saturated cell weighs its fluid share 1 − B λ only
    real drag_x = 0, drag_y = 0, drag_z = 0, weighed = 1;
#if SOLID
    // a cell a solid covers: B = ε (τ − ½) / ((1 − ε) + (τ − ½)) with the cell's last τ (1 where ε = 1),
    // weighted by λ (lbm::saturation_weight, FluidLattice::coupling_weight)
    const real eps = solid_fraction[k];
    if (eps > (real)0) {
        const real last = (BINGHAM || LES) ? tau[k] : (real)TAU, excess = last - (real)0.5;
#if FREE_SURFACE
        const real lambda = t_k == INTERFACE ? clamp(fill[k], (real)0, (real)1) : (real)1;
#else
        const real lambda = (real)1;
#endif
        SolidDrag sd;
        sd.w = lambda * (eps >= (real)1 ? (real)1 : eps * excess / (((real)1 - eps) + excess));
        sd.vx = solid_v[3 * k];
        sd.vy = solid_v[3 * k + 1];
        sd.vz = solid_v[3 * k + 2];
        collide(fl, &t, &clamped, ax, ay, az, &sd);
        drag_x = -sd.hx;
        drag_y = -sd.hy;
        drag_z = -sd.hz;
        if (SOLID == 2) weighed = (real)1 - sd.w;
        solid_force[3 * k] = (acc)sd.hx;
        solid_force[3 * k + 1] = (acc)sd.hy;
        solid_force[3 * k + 2] = (acc)sd.hz;
    } else {
        collide(fl, &t, &clamped, ax, ay, az, 0);
    }
#else
    collide(fl, &t, &clamped, ax, ay, az, 0);
#endif
#if BINGHAM || LES
    tau[k] = t;
#endif
#if BINGHAM
    if (clamped < 0) atomic_inc(&counts[0]);
    if (clamped > 0) atomic_inc(&counts[1]);
#endif
#if FREE_SURFACE
    if (t_k == INTERFACE) {
        // the density and velocity of the collision ((j* − F/2)/ρ from the populations after it) and the
        // outgoing populations as the lattice holds them, for the mass exchange and the next reconstruction
        real jx = 0, jy = 0, jz = 0;
#pragma unroll
        for (int i = 1; i < Q; ++i) {
            jx += (real)CX[i] * fl[i];
            jy += (real)CY[i] * fl[i];
            jz += (real)CZ[i] * fl[i];
            out[i * (long)CELLS + k] = fl[i];
        }
        out[k] = fl[0];
        const real rho = (real)rho_surface;
        srho[k] = rho_surface;
        su[3 * k] = (jx - (real)0.5 * (weighed * rho * ax + drag_x)) / rho;
        su[3 * k + 1] = (jy - (real)0.5 * (weighed * rho * ay + drag_y)) / rho;
        su[3 * k + 2] = (jz - (real)0.5 * (weighed * rho * az + drag_z)) / rho;
        out_known[k] = 1;
    }
#endif
    uint slot = lk != 0u ? link_start[k] : 0u;
#pragma unroll
    for (int i = 0; i < Q; ++i) {
        const int o = OPPOSITE(i);
        const real post = fl[i];
        if ((lk >> i) & 1u) {
            // bounce-back: the momentum given to the obstacle along c_i relative to the atmosphere
            // (post + back as deviations from rest), the returned population back into this cell
            const int e = element_of(neighbour(x, y, z, i, 1), type, element);
            const real back = post - wall_term(i, e, wall_u);
            link_momentum[slot++] = (acc)post + (acc)back;
            f[o * (long)SLOT + k] = odd ? back : post;
        } else if (odd) {
            f[i * (long)SLOT + neighbour(x, y, z, i, 1)] = post;
        } else {
            f[o * (long)SLOT + k] = post;
        }
    }
}

// The τ clamp and updated-cell counts of a work-group: one integer addition per group and count (integers:
// the order does not matter).
#define STEP_KERNEL(name, odd)                                                                                \
    kernel void name(global real* f, global real* tau, global const uchar* type, global const uint* links,    \
                     global const ushort* element, global const real* wall_u, global const uint* link_start, \
                     global acc* link_momentum, global uint* counters, real ax, real ay,                      \
                     real az SURFACE_PARAMS SOLID_PARAMS) {                                                   \
        local uint counts[3];                                                                                 \
        const int first = get_local_id(0) == 0 && get_local_id(1) == 0 && get_local_id(2) == 0;              \
        if (first) counts[0] = counts[1] = counts[2] = 0u;                                                    \
        barrier(CLK_LOCAL_MEM_FENCE);                                                                         \
        step_cell(odd, f, tau, type, links, element, wall_u, link_start, link_momentum, counts, ax, ay,      \
                  az SURFACE_ARGS SOLID_ARGS);                                                                \
        barrier(CLK_LOCAL_MEM_FENCE);                                                                         \
        if (first)                                                                                            \
            for (int c = 0; c < 3; ++c)                                                                       \
                if (counts[c] != 0u) atomic_add(&counters[c], counts[c]);                                     \
    }
STEP_KERNEL(stream_collide_even, 0)
STEP_KERNEL(stream_collide_odd, 1)

// The force on each element in two passes, each in a fixed order (the same every step and every run):
// reduce_link_chunks: work-group c sums the momenta of chunk c of the wall links (element_links from
// chunk_begin[c] to chunk_begin[c + 1], each with its direction in link_direction; an element's links are
// consecutive, cut into chunks of at most a few thousand so that a large element, such as the channel's
// walls, is summed by many groups), every work-item a strided share, then a tree over the group;
// sum_element_chunks: work-group e adds element e's chunks (element_chunk[e] to element_chunk[e + 1]) in the
// same way (the walls' element can have thousands).
// The work-group's sum of its items' (sx, sy, sz) as a tree, the same order every time, into out[0..3).
inline void group_sum3(acc sx, acc sy, acc sz, local acc* partial, global acc* out) {
    const int l = get_local_id(0), n = get_local_size(0);
    partial[3 * l] = sx;
    partial[3 * l + 1] = sy;
    partial[3 * l + 2] = sz;
    for (int span = n / 2; span > 0; span /= 2) {
        barrier(CLK_LOCAL_MEM_FENCE);
        if (l < span)
            for (int a = 0; a < 3; ++a) partial[3 * l + a] += partial[3 * (l + span) + a];
    }
    if (l == 0)
        for (int a = 0; a < 3; ++a) out[a] = partial[a];
}

kernel void reduce_link_chunks(global const acc* link_momentum, global const uint* element_links,
                               global const uchar* link_direction, global const uint* chunk_begin,
                               global acc* chunk_sums, local acc* partial) {
    const int c = get_group_id(0), l = get_local_id(0), n = get_local_size(0);
    acc sx = 0, sy = 0, sz = 0;
    for (uint j = chunk_begin[c] + l; j < chunk_begin[c + 1]; j += n) {
        const acc m = link_momentum[element_links[j]];
        const int i = link_direction[j];
        sx += (acc)CX[i] * m;
        sy += (acc)CY[i] * m;
        sz += (acc)CZ[i] * m;
    }
    group_sum3(sx, sy, sz, partial, chunk_sums + 3 * c);
}

kernel void sum_element_chunks(global const uint* element_chunk, global const acc* chunk_sums,
                               global acc* forces, local acc* partial) {
    const int e = get_group_id(0), l = get_local_id(0), n = get_local_size(0);
    acc sx = 0, sy = 0, sz = 0;
    for (uint c = element_chunk[e] + l; c < element_chunk[e + 1]; c += n) {
        sx += chunk_sums[3 * c];
        sy += chunk_sums[3 * c + 1];
        sz += chunk_sums[3 * c + 2];
    }
    group_sum3(sx, sy, sz, partial, forces + 3 * e);
}

// The momenta of the links listed in `links` (indices of link_momentum: a mesh barrier's links, in the host's
// BarrierLinks order), copied together so that the host reads them alone.
kernel void gather_link_momenta(global const acc* link_momentum, global const uint* links, global acc* out,
                                uint count) {
    const uint j = get_global_id(0);
    if (j < count) out[j] = link_momentum[links[j]];
}

// The macroscopic fields of the cells of planes [x_begin, x_end) in image order (x fastest, no padding), what
// observers and frames read (lbm/fluid_fields.h; the host adds up the totals in the CPU lattice's order): type, λ, τ, ρ and u
// (a fluid cell's from its incoming populations, u = (j + F/2)/ρ; an interface cell's last collision's) and
// the cell's mass (ρ, or an interface cell's tracked m).
#if FREE_SURFACE
#define SNAPSHOT_SURFACE_PARAMS , global const real *fill, global const acc *mass, global const acc *srho, global const real *su
#else
#define SNAPSHOT_SURFACE_PARAMS
#endif
// a cell a moving solid covers (its fluid moves with the solid: observers count it apart)
#if SOLID
#define COVER_PARAMS , global const real *solid_fraction
#define SNAPSHOT_COVER_PARAMS , global const real *solid_fraction, global uchar *out_covered
#else
#define COVER_PARAMS
#define SNAPSHOT_COVER_PARAMS
#endif
kernel void snapshot_fields(const int odd, const int x_begin, const int x_end, global const real* f,
                            global const real* tau, global const uchar* type, global const uint* links,
                            global const ushort* element, global const real* wall_u, real ax, real ay, real az,
                            global uchar* out_type, global real* out_fill, global real* out_tau,
                            global acc* out_rho, global real* out_u,
                            global acc* out_mass SNAPSHOT_SURFACE_PARAMS SNAPSHOT_COVER_PARAMS) {
    const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
    if (x < x_begin || x >= x_end) return;
    const long k = (long)x + (long)ROW * y + (long)PLANE * z;
    const long c = (long)(x - x_begin) + (long)(x_end - x_begin) * (y + (long)NY * z);
    const uchar t = type[k];
    out_type[c] = t;
    out_tau[c] = tau[k];
#if SOLID
    out_covered[c] = solid_fraction[k] > (real)0 ? 1 : 0;
#endif
#if FREE_SURFACE
    out_fill[c] = fill[k];
#else
    out_fill[c] = t == FLUID ? (real)1 : (real)0;
#endif
    acc rho = 0, m = 0;
    real u[3] = {0, 0, 0};
    if (t == FLUID) {
        fluid_moments(odd, x, y, z, k, f, type, links, element, wall_u, ax, ay, az, &rho, u);
        m = rho;
    }
#if FREE_SURFACE
    else if (t == INTERFACE) {
        rho = srho[k];
        m = mass[k];
        for (int a = 0; a < 3; ++a) u[a] = su[3 * k + a];
    }
#endif
    out_rho[c] = rho;
    out_mass[c] = m;
    for (int a = 0; a < 3; ++a) out_u[3 * c + a] = u[a];
}

// The sums a series row reads (lbm/fluid_summary.h) without the fields: work-item g of the fixed grid takes
// the stored cells g, g + G, g + 2G, … in order, the work-group a tree, the host the groups in order. Per
// group: the wet cells' mass (ρ, or an interface cell's m), their λρ, the λρ of those downstream, the
// largest speed (into sums), the interface cells, and the highest x and z of a wet cell with λ ≥ 0.1
// (into counts; −1: none); the λρ sums leave out the cells a moving solid covers.
#define SUMMARY_SUMS 4
#define SUMMARY_COUNTS 3
#if FREE_SURFACE
#define SUMMARY_SURFACE_PARAMS , global const real *fill, global const acc *mass, global const acc *srho, global const real *su
#else
#define SUMMARY_SURFACE_PARAMS
#endif
kernel void summarize_cells(const int odd, global const real* f, global const uchar* type, global const uint* links,
                            global const ushort* element, global const real* wall_u, real ax, real ay, real az,
                            global const uchar* region, global acc* group_sums, global int* group_counts,
                            local acc* partial, local int* counts SUMMARY_SURFACE_PARAMS COVER_PARAMS) {
    const int l = get_local_id(0), n = get_local_size(0);
    acc s[SUMMARY_SUMS] = {0, 0, 0, 0};
    int c[SUMMARY_COUNTS] = {0, -1, -1};
    for (long k = get_global_id(0); k < CELLS; k += get_global_size(0)) {
        const int x = (int)(k % ROW), y = (int)((k / ROW) % NY), z = (int)(k / PLANE);
        if (x < OWN_BEGIN || x >= OWN_END) continue;  // (a slab's ghost planes are its neighbours')
        const uchar t = type[k];
        if (t != FLUID && t != INTERFACE) continue;
        acc rho, m;
        real lambda = (real)1, u2;
        if (t == FLUID) {
            real u[3];
            fluid_moments(odd, x, y, z, k, f, type, links, element, wall_u, ax, ay, az, &rho, u);
            m = rho;
            u2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
        }
#if FREE_SURFACE
        else {
            rho = srho[k];
            m = mass[k];
            lambda = fill[k];
            u2 = su[3 * k] * su[3 * k] + su[3 * k + 1] * su[3 * k + 1] + su[3 * k + 2] * su[3 * k + 2];
            ++c[0];
        }
#endif
        const acc own = (acc)lambda * rho;
        s[0] += m;
#if SOLID
        const int covered = solid_fraction[k] > (real)0;
#else
        const int covered = 0;
#endif
        if (!covered) {
            s[1] += own;
            if ((region[k] & 1) != 0) s[2] += own;  // (RegionBits: region_downstream)
        }
        s[3] = fmax(s[3], (acc)sqrt(u2));
        if (lambda >= (real)0.1) {
            c[1] = max(c[1], x);
            c[2] = max(c[2], z);
        }
    }
    for (int a = 0; a < SUMMARY_SUMS; ++a) partial[SUMMARY_SUMS * l + a] = s[a];
    for (int a = 0; a < SUMMARY_COUNTS; ++a) counts[SUMMARY_COUNTS * l + a] = c[a];
    for (int span = n / 2; span > 0; span /= 2) {
        barrier(CLK_LOCAL_MEM_FENCE);
        if (l < span) {
            local acc* p = partial + SUMMARY_SUMS * l;
            local const acc* q = partial + SUMMARY_SUMS * (l + span);
            local int* a = counts + SUMMARY_COUNTS * l;
            local const int* b = counts + SUMMARY_COUNTS * (l + span);
            for (int i = 0; i < 3; ++i) p[i] += q[i];
            p[3] = fmax(p[3], q[3]);
            a[0] += b[0];
            a[1] = max(a[1], b[1]);
            a[2] = max(a[2], b[2]);
        }
    }
    if (l == 0) {
        for (int a = 0; a < SUMMARY_SUMS; ++a) group_sums[SUMMARY_SUMS * get_group_id(0) + a] = partial[a];
        for (int a = 0; a < SUMMARY_COUNTS; ++a) group_counts[SUMMARY_COUNTS * get_group_id(0) + a] = counts[a];
    }
}

#if SOLID
// The cells a moving solid covers, set from a list (FluidLattice::set_solid_cells' form: storage index,
// velocity at the cell's centre, share ε): the last list's cells cleared first.
kernel void clear_solid_cells(const uint n, global const uint* cell, global real* solid_fraction) {
    const uint g = get_global_id(0);
    if (g < n) solid_fraction[cell[g]] = 0;
}

kernel void scatter_solid_cells(const uint n, global const uint* cell, global const real* fraction,
                                global const real* velocity, global real* solid_fraction, global real* solid_v) {
    const uint g = get_global_id(0);
    if (g >= n) return;
    const uint k = cell[g];
    solid_fraction[k] = fraction[g];
    for (int a = 0; a < 3; ++a) solid_v[3 * k + a] = velocity[3 * g + a];
}

// The force on the solid from each listed cell in the last step, in the list's order.
kernel void gather_solid_forces(const uint n, global const uint* cell, global const acc* solid_force,
                                global acc* forces) {
    const uint g = get_global_id(0);
    if (g >= n) return;
    for (int a = 0; a < 3; ++a) forces[3 * g + a] = solid_force[3 * cell[g] + a];
}
#endif
