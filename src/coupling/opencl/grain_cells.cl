// SPDX-License-Identifier: MIT
// The cells each grain covers, found on the lattice's device (coupling/opencl/device_grain_cells.h): the
// rules of coupling/grain_cells.h — a cell belongs to a grain whose sphere holds its centre (CELL_CENTRE)
// or that cuts it (PSM, with the share ε of its volume inside); a cell two grains claim goes to the one
// holding more of it (PSM), then to the one it lies deeper in (the smaller |x_c − x_p|² / r_p²), then to the
// lower index. Each pass runs one work-group per grain over the cells of its bounding box and settles one
// criterion with an atomic maximum or minimum on the bits of a non-negative double (their order is the
// numbers'), so the result does not depend on which grain comes first:
//   claim_fraction   (PSM) the largest ε a grain gives the cell
//   claim_depth      among the grains giving that ε, the smallest depth
//   claim_grain      among those, the lowest index: the owner
//   release          the cells of the grains' boxes back to unclaimed (before the grains move)
// Built with the lattice's options (NX, NY, NZ, ROW, PLANE) and PSM 0/1; positions in double, m.
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#pragma OPENCL EXTENSION cl_khr_int64_extended_atomics : enable

typedef REAL real;  // the lattice's storage
typedef ACC acc;    // its force sums

#define HALF_DIAGONAL 0.86602540378443865  // a cell's centre to its corners, in cells
#define COLUMNS 89                          // solid_fraction()'s columns (a Fibonacci lattice)
#define UNCLAIMED_DEPTH 0xffffffffffffffffUL
#define NO_GRAIN 0xffffffffu

// The share of the unit cube centred at d inside the sphere of radius rc centred at the origin (cell
// units): coupling::solid_fraction's columns, in its order.
inline double solid_fraction(double dx, double dy, double dz, double rc) {
    const double distance = sqrt(dx * dx + dy * dy + dz * dz);
    if (distance + HALF_DIAGONAL <= rc) return 1.0;
    if (distance - HALF_DIAGONAL >= rc) return 0.0;
    const double rc2 = rc * rc;
    double length = 0.0;
    for (int c = 0; c < COLUMNS; ++c) {
        const double x = dx + ((c + 0.5) / COLUMNS - 0.5), y = dy + ((c * 55 % COLUMNS + 0.5) / COLUMNS - 0.5);
        const double h = sqrt(fmax(rc2 - x * x - y * y, 0.0));
        length += fmax(0.0, fmin(dz + 0.5, h) - fmax(dz - 0.5, -h));
    }
    return fmin(1.0, length / COLUMNS);
}

// A grain's claim on the cells of its box: what a pass needs of one cell
typedef struct {
    long k;              // stored index
    double fraction;     // ε (1 by the cell-centre rule; 0: not claimed)
    double depth;        // |x_c − x_p|² / r_p²
    double dx, dy, dz;   // x_c − x_p, m
} Claim;

// Cell number `i` of grain g's box (x fastest) and the grain's claim on it.
inline Claim claim_of(int i, int g, global const double* x, global const double* r, double ox, double oy,
                      double oz, double dx, int* in_box) {
    const double inv = 1.0 / dx;
    const double px = x[3 * g] - ox, py = x[3 * g + 1] - oy, pz = x[3 * g + 2] - oz, rg = r[g];
    const double out = PSM ? rg + HALF_DIAGONAL * dx : rg;
    const int x0 = clamp((int)ceil((px - out) * inv - 0.5), 0, NX), x1 = clamp((int)floor((px + out) * inv - 0.5) + 1, 0, NX);
    const int y0 = clamp((int)ceil((py - out) * inv - 0.5), 0, NY), y1 = clamp((int)floor((py + out) * inv - 0.5) + 1, 0, NY);
    const int z0 = clamp((int)ceil((pz - out) * inv - 0.5), 0, NZ), z1 = clamp((int)floor((pz + out) * inv - 0.5) + 1, 0, NZ);
    Claim c = {-1, 0.0, 0.0, 0.0, 0.0, 0.0};
    const int wx = x1 - x0, wy = y1 - y0, wz = z1 - z0;
    *in_box = wx > 0 && wy > 0 && wz > 0 && i < wx * wy * wz;
    if (!*in_box) return c;
    const int cx = x0 + i % wx, cy = y0 + (i / wx) % wy, cz = z0 + i / (wx * wy);
    c.k = (long)cx + (long)ROW * cy + (long)PLANE * cz;
    // the cell's centre relative to the grain's, m (LatticeFrame::centre − x_p)
    const double ddx = (ox + (cx + 0.5) * dx) - x[3 * g], ddy = (oy + (cy + 0.5) * dx) - x[3 * g + 1],
                 ddz = (oz + (cz + 0.5) * dx) - x[3 * g + 2];
    const double d2 = ddx * ddx + ddy * ddy + ddz * ddz;
    c.dx = ddx;
    c.dy = ddy;
    c.dz = ddz;
    if (d2 >= out * out) return c;
    c.fraction = PSM ? solid_fraction(ddx * inv, ddy * inv, ddz * inv, rg * inv) : 1.0;
    c.depth = d2 / (rg * rg);
    return c;
}

// The cells of a grain's box, at most: (2 out / dx + 2)³ (the host sizes `box_cells` by the largest grain)
#define FOR_EACH_CLAIM(...)                                                              \
    const int g = get_group_id(0);                                                        \
    for (int i = get_local_id(0); i < box_cells; i += get_local_size(0)) {                \
        int in_box;                                                                       \
        const Claim c = claim_of(i, g, x, r, ox, oy, oz, dx, &in_box);                    \
        if (!in_box) break;                                                               \
        if (c.fraction <= 0.0) continue;                                                  \
        __VA_ARGS__                                                                       \
    }

#define CLAIM_PARAMS                                                                                   \
    const int box_cells, global const double *x, global const double *r, const double ox, const double oy, \
        const double oz, const double dx

kernel void claim_fraction(CLAIM_PARAMS, global ulong* fraction) {
    FOR_EACH_CLAIM(atom_max(&fraction[c.k], as_ulong(c.fraction));)
}

kernel void claim_depth(CLAIM_PARAMS, global const ulong* fraction, global ulong* depth) {
    FOR_EACH_CLAIM(if (!PSM || as_ulong(c.fraction) == fraction[c.k]) atom_min(&depth[c.k], as_ulong(c.depth));)
}

kernel void claim_grain(CLAIM_PARAMS, global const ulong* fraction, global const ulong* depth, global uint* owner) {
    FOR_EACH_CLAIM(if ((!PSM || as_ulong(c.fraction) == fraction[c.k]) && as_ulong(c.depth) == depth[c.k])
                       atomic_min(&owner[c.k], (uint)g);)
}

kernel void release(CLAIM_PARAMS, global ulong* fraction, global ulong* depth, global uint* owner) {
    FOR_EACH_CLAIM(fraction[c.k] = 0; depth[c.k] = UNCLAIMED_DEPTH; owner[c.k] = NO_GRAIN;)
}

// The sums of a work-group's items' s[0..n) as a tree, the same order every time, into out[0..n).
#define MAX_SUMS 7
inline void group_sums(const double* s, const int count, local double* partial, global double* out) {
    const int l = get_local_id(0), n = get_local_size(0);
    for (int a = 0; a < count; ++a) partial[MAX_SUMS * l + a] = s[a];
    for (int span = n / 2; span > 0; span /= 2) {
        barrier(CLK_LOCAL_MEM_FENCE);
        if (l < span)
            for (int a = 0; a < count; ++a) partial[MAX_SUMS * l + a] += partial[MAX_SUMS * (l + span) + a];
    }
    if (l == 0)
        for (int a = 0; a < count; ++a) out[a] = partial[a];
}

#if SOLID
// Grain g's cells, covered for the lattice's step (its solid_fraction and solid_v, lbm/opencl): the share ε
// and the grain's surface velocity v + ω × (x_c − x_p) in lattice units; and the grain's buoyancy weight
// Σ λ (ε − B) over them (GrainFluidCoupling: λ the cell's fill, B the partially saturated share carried by
// the exchange, from the cell's last τ; 0 by the cell-centre rule), before the step.
kernel void cover_cells(CLAIM_PARAMS, global const double* v, global const double* w, const double dt,
                        global const ulong* fraction, global const uint* owner, global const uchar* type,
                        global const real* tau, global real* solid_fraction, global real* solid_v,
                        global double* weights, local double* partial
#if FREE_SURFACE
                        , global const real* fill
#endif
) {
    double weight = 0.0;
    FOR_EACH_CLAIM(
        if (owner[c.k] == (uint)g) {
            const double eps = PSM ? as_double(fraction[c.k]) : 1.0;
            const double vx = v[3 * g] + (w[3 * g + 1] * c.dz - w[3 * g + 2] * c.dy);
            const double vy = v[3 * g + 1] + (w[3 * g + 2] * c.dx - w[3 * g] * c.dz);
            const double vz = v[3 * g + 2] + (w[3 * g] * c.dy - w[3 * g + 1] * c.dx);
            solid_fraction[c.k] = (real)eps;
            solid_v[3 * c.k] = (real)(vx * dt / dx);
            solid_v[3 * c.k + 1] = (real)(vy * dt / dx);
            solid_v[3 * c.k + 2] = (real)(vz * dt / dx);
            const uchar t = type[c.k];
#if FREE_SURFACE
            const double lambda = t == 0 || t == 1 ? clamp((double)fill[c.k], 0.0, 1.0) : 0.0;
#else
            const double lambda = t == 0 ? 1.0 : 0.0;
#endif
            const double excess = (double)tau[c.k] - 0.5;
            const double carried = !PSM ? 0.0 : (eps >= 1.0 ? 1.0 : eps * excess / ((1.0 - eps) + excess));
            // (a slab's ghost cells are stepped covered, but their weight and forces are the neighbour's,
            // who owns them)
            const int own_x = (int)(c.k % ROW);
            if (own_x >= OWN_BEGIN && own_x < OWN_END) weight += lambda * (eps - carried);
        })
    group_sums(&weight, 1, partial, weights + g);
}

// Before the grains move: their cells uncovered.
kernel void uncover_cells(CLAIM_PARAMS, global const uint* owner, global real* solid_fraction) {
    FOR_EACH_CLAIM(if (owner[c.k] == (uint)g) solid_fraction[c.k] = 0;)
}

// After the step: grain g's F_h = Σ of its cells' forces (lattice units), Σ (x_c − x_p) × F_h (m times
// those) and its cells, in a fixed order.
kernel void grain_forces(CLAIM_PARAMS, global const uint* owner, global const acc* solid_force,
                         global double* sums, local double* partial) {
    double s[7] = {0, 0, 0, 0, 0, 0, 0};
    FOR_EACH_CLAIM(
        // (a slab's ghost cells are stepped covered, but their forces are the neighbour's, who owns them)
        const int own_x = (int)(c.k % ROW);
        if (owner[c.k] == (uint)g && own_x >= OWN_BEGIN && own_x < OWN_END) {
            const double fx = solid_force[3 * c.k], fy = solid_force[3 * c.k + 1], fz = solid_force[3 * c.k + 2];
            s[0] += fx;
            s[1] += fy;
            s[2] += fz;
            s[3] += c.dy * fz - c.dz * fy;
            s[4] += c.dz * fx - c.dx * fz;
            s[5] += c.dx * fy - c.dy * fx;
            s[6] += 1.0;
        })
    group_sums(s, 7, partial, sums + 7 * g);
}
#endif
