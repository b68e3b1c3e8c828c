// SPDX-License-Identifier: MIT
// The free surface on an OpenCL device (docs/lbm.md, "Backends"): the CPU lattice's mass tracking
// (src/lbm/free_surface.cpp) as a chain of cell-parallel kernels, each reading only what the ones before it
// wrote, so no cell reads what another writes in the same kernel. After the sweep (stream_collide_*,
// which collides the interface cells with the reconstructed gas-side populations and records their
// density, velocity and outgoing populations):
//   surface_exchange   the mass each interface cell exchanged through the populations just streamed; the
//                      new λ (into new_fill) and whether the cell fills (+1, +2 enclosed) or empties (−1)
//   surface_neighbours λ takes its new value; an emptying cell next to a filling one stays (filling
//                      wins); gas next to a filling cell is to be born
//   surface_demote     fluid next to an emptying cell is to be demoted; converting cells take their normal
//   surface_mark       a demoted cell takes its ρ, u; a cell to be born the mean ρ, u of its wet neighbours
//   surface_convert    born cells become interface (equilibrium populations, m = 0), demoted ones
//                      interface (m = ρ), emptied ones gas (their mass is the excess)
//   surface_fill       filled cells become fluid at the density of their incoming populations (their
//                      mass beyond it is the excess)
//   surface_shares     each converted cell's weights toward its interface neighbours, or its excess as
//                      an orphan (no interface neighbour, or a closed gas pocket)
//   surface_gather     each interface cell takes its shares of its converted neighbours' excess
//   sum_orphans, spread_orphans   the orphans' total over the interface cells (fixed-order sums)
//   surface_finish     λ = m/ρ
//   surface_prepare    the outgoing populations of the new interface cells and every interface cell's normal
// `odd` is the parity of the steps done (after the sweep), which says where the populations are.
#if FREE_SURFACE

#define NONE 0
#define BORN 1
#define DEMOTED 2
#define EMPTIED 3
#define FILLED 4
#define ENCLOSED 5

// The surface kernels take XCELLS consecutive cells of a row per work-item: most cells leave them at once
// (gas, bulk fluid), and a GPU then spends its time starting work-items, each waiting on one load; a
// work-item that walks a few cells of the same cache line waits once. A skipped cell `continue`s.
#define CELL_LOOP_BEGIN                                                    \
    const int y = get_global_id(1), z = get_global_id(2);                 \
    const int x_first = (int)get_global_id(0) * XCELLS;                   \
    for (int x = x_first; x < x_first + XCELLS && x < NX; ++x) {          \
        const long k = (long)x + (long)ROW * y + (long)PLANE * z;
#define CELL_LOOP_END }

// f_j(k) before the next collision, as a deviation from rest (the CPU's incoming()).
inline real incoming(const int odd, int x, int y, int z, long k, int j, global const real* f,
                     global const uchar* type, global const ushort* element, global const real* wall_u) {
    if (!odd) return f[j * (long)SLOT + k];
    const int o = OPPOSITE(j);
    const long src = neighbour(x, y, z, j, -1);
    if (src < 0 || type[src] == OBSTACLE) return f[j * (long)SLOT + k] - wall_term(o, element_of(src, type, element), wall_u);
    return f[o * (long)SLOT + src];
}

// f_i*(k) after the last collision (the CPU's outgoing()) and its replacement (set_outgoing()).
inline real outgoing(const int odd, int x, int y, int z, long k, int i, global const real* f,
                     global const uchar* type, global const ushort* element, global const real* wall_u) {
    const int o = OPPOSITE(i);
    if (odd) return f[o * (long)SLOT + k];
    const long dst = neighbour(x, y, z, i, 1);
    if (dst < 0 || type[dst] == OBSTACLE) return f[o * (long)SLOT + k] + wall_term(i, element_of(dst, type, element), wall_u);
    return f[i * (long)SLOT + dst];
}

inline void set_outgoing(const int odd, int x, int y, int z, long k, int i, real value, global real* f,
                         global const uchar* type, global const ushort* element, global const real* wall_u) {
    const int o = OPPOSITE(i);
    if (odd) {
        f[o * (long)SLOT + k] = value;
        return;
    }
    const long dst = neighbour(x, y, z, i, 1);
    if (dst < 0 || type[dst] == OBSTACLE)
        f[o * (long)SLOT + k] = value - wall_term(i, element_of(dst, type, element), wall_u);
    else
        f[i * (long)SLOT + dst] = value;
}

// ρ and u of a wet cell: a fluid cell's from its incoming populations, an interface cell's last collision's
inline void moments(const int odd, int x, int y, int z, long k, global const real* f, global const uchar* type,
                    global const uint* links, global const ushort* element, global const real* wall_u,
                    global const acc* srho, global const real* su, real ax, real ay, real az, acc* rho, real* u) {
    if (type[k] != INTERFACE) {
        fluid_moments(odd, x, y, z, k, f, type, links, element, wall_u, ax, ay, az, rho, u);
        return;
    }
    *rho = srho[k];
    for (int a = 0; a < 3; ++a) u[a] = su[3 * k + a];
}

// n = −∇λ by central differences; a solid neighbour counts with the cell's own λ
inline void surface_normal(int x, int y, int z, long k, global const uchar* type, global const real* fill,
                           real* n) {
    real l[7];
    l[0] = fill[k];
    for (int i = 1; i < 7; ++i) {
        const long m = neighbour(x, y, z, i, 1);
        l[i] = (m < 0 || type[m] == OBSTACLE) ? l[0] : fill[m];
    }
    n[0] = (real)-0.5 * (l[1] - l[2]);
    n[1] = (real)-0.5 * (l[3] - l[4]);
    n[2] = (real)-0.5 * (l[5] - l[6]);
}

kernel void surface_exchange(const int odd, global const real* f, global const uchar* type,
                             global const real* fill, global real* new_fill, global acc* mass,
                             global const acc* srho, global const real* out, global char* convert,
                             global const uchar* outlet, global uchar* change) {
    CELL_LOOP_BEGIN
    change[k] = NONE;  // (this step's conversions are marked by the kernels after this one)
    if (type[k] != INTERFACE) continue;
    const real own = fill[k];
    acc dm = 0;
    int touches_gas = 0, touches_fluid = 0;
    for (int i = 1; i < Q; ++i) {
        const long n = neighbour(x, y, z, i, 1);
        if (n < 0) continue;
        const uchar t = type[n];
        if (t == OBSTACLE) continue;
        if (t == GAS) {
            touches_gas = 1;
            continue;
        }
        touches_fluid |= t == FLUID;
        const real alpha = t == FLUID ? (real)1 : (real)0.5 * (own + fill[n]);
        // Δm_i = α (f_ī arrived from n − f_i* sent toward n), both streamed in the step just done
        const real in = odd ? f[i * (long)SLOT + n] : f[OPPOSITE(i) * (long)SLOT + k];
        dm += (acc)alpha * ((acc)in - (acc)out[i * (long)CELLS + k]);
    }
    const acc m = mass[k] + dm, rho = srho[k];
    mass[k] = m;
    new_fill[k] = (real)(m / rho);
    char c = m > ((acc)1 + (acc)SURFACE_EPSILON) * rho ? 1 : (m < -(acc)SURFACE_EPSILON * rho ? -1 : 0);
    if (c == 0 && !touches_gas) c = 2;    // left inside the fluid: fluid whatever its mass
    if (c == 0 && !touches_fluid) c = -1;  // spray: empties unless over-full
    if (outlet[k] != 0) c = -1;            // what reaches an outlet leaves the domain
    convert[k] = c;
    CELL_LOOP_END
}

// Scattered from the few cells that convert rather than gathered by every cell (most of the lattice is
// gas or bulk fluid, which then reads only its own type): a filling cell marks its gas neighbours to be
// born and keeps its emptying neighbours (filling wins: only −1 → 0 is written, so the cells that test
// convert > 0 are not affected by these writes; several writers write the same value).
kernel void surface_neighbours(global const uchar* type, global real* fill, global const real* new_fill,
                               global char* convert, global uchar* change) {
    CELL_LOOP_BEGIN
    if (type[k] != INTERFACE) continue;
    fill[k] = new_fill[k];
    if (convert[k] <= 0) continue;
    for (int i = 1; i < Q; ++i) {
        const long n = neighbour(x, y, z, i, 1);
        if (n < 0) continue;
        const uchar t = type[n];
        if (t == GAS) change[n] = BORN;
        else if (t == INTERFACE && convert[n] < 0) convert[n] = 0;
    }
    CELL_LOOP_END
}

// An emptying cell (its convert now final) marks its fluid neighbours to be demoted to interface; every
// converting interface cell takes its normal (from λ, all updated by surface_neighbours).
kernel void surface_demote(global const uchar* type, global const real* fill, global const char* convert,
                           global uchar* change, global real* normal) {
    CELL_LOOP_BEGIN
    if (type[k] != INTERFACE || convert[k] == 0) continue;
    if (convert[k] < 0)
        for (int i = 1; i < Q; ++i) {
            const long n = neighbour(x, y, z, i, 1);
            if (n >= 0 && type[n] == FLUID) change[n] = DEMOTED;
        }
    real nv[3];
    surface_normal(x, y, z, k, type, fill, nv);
    for (int a = 0; a < 3; ++a) normal[3 * k + a] = nv[a];
    CELL_LOOP_END
}

// A demoted cell takes its ρ, u; a cell to be born the mean ρ, u of its wet neighbours.
kernel void surface_mark(const int odd, global const real* f, global const uchar* type, global const uint* links,
                         global const ushort* element,
                         global const real* wall_u, global const uchar* change, global acc* srho, global real* su,
                         real ax, real ay, real az) {
    CELL_LOOP_BEGIN
    const uchar c = change[k];
    if (c == DEMOTED) {
        acc rho;
        real u[3];
        moments(odd, x, y, z, k, f, type, links, element, wall_u, srho, su, ax, ay, az, &rho, u);
        srho[k] = rho;
        for (int a = 0; a < 3; ++a) su[3 * k + a] = u[a];
    } else if (c == BORN) {
        // f^eq(ρ̄, ū) of the wet neighbours' mean (the cell's own ρ, u slots are free: it is gas)
        acc rho_sum = 0;
        real u_sum[3] = {0, 0, 0};
        int count = 0;
        for (int i = 1; i < Q; ++i) {
            const long n = neighbour(x, y, z, i, 1);
            if (n < 0 || type[n] == OBSTACLE || type[n] == GAS) continue;
            const int nz_ = (int)(n / PLANE), ny_ = (int)((n % PLANE) / ROW), nx_ = (int)(n % ROW);
            acc rho;
            real u[3];
            moments(odd, nx_, ny_, nz_, n, f, type, links, element, wall_u, srho, su, ax, ay, az, &rho, u);
            rho_sum += rho;
            for (int a = 0; a < 3; ++a) u_sum[a] += u[a];
            ++count;
        }
        srho[k] = count > 0 ? rho_sum / (acc)count : (acc)1;
        for (int a = 0; a < 3; ++a) su[3 * k + a] = count > 0 ? u_sum[a] / (real)count : (real)0;
    }
    CELL_LOOP_END
}

kernel void surface_convert(const int odd, global real* f, global real* tau, global uchar* type,
                            global const ushort* element, global const real* wall_u, global real* fill,
                            global acc* mass, global const char* convert, global uchar* change,
                            global const acc* srho, global const real* su, global uchar* out_known,
                            global acc* excess, global uint* counters) {
    CELL_LOOP_BEGIN
    const uchar c = change[k];
    if (c == BORN) {
        type[k] = INTERFACE;
        fill[k] = 0;
        mass[k] = 0;
        tau[k] = (real)(BINGHAM ? TAU_MAX : TAU);
        out_known[k] = 0;
        const real rho = (real)srho[k], ux = su[3 * k], uy = su[3 * k + 1], uz = su[3 * k + 2];
        const real u2 = (real)1.5 * (ux * ux + uy * uy + uz * uz);
        // f_i^eq(ρ, u) − w_i
        for (int i = 0; i < Q; ++i) {
            const real cu = (real)CX[i] * ux + (real)CY[i] * uy + (real)CZ[i] * uz;
            const real w = WEIGHT(i);
            set_outgoing(odd, x, y, z, k, i, w * (rho * ((real)1 + (real)3 * cu + (real)4.5 * cu * cu - u2) - (real)1),
                         f, type, element, wall_u);
        }
    } else if (c == DEMOTED) {
        type[k] = INTERFACE;
        mass[k] = srho[k];
        fill[k] = 1;
        out_known[k] = 0;
    } else if (type[k] == INTERFACE && convert[k] < 0) {
        change[k] = EMPTIED;
        atomic_inc(&counters[4]);
        excess[k] = mass[k];
        type[k] = GAS;
        mass[k] = 0;
        fill[k] = 0;
    }
    CELL_LOOP_END
}

kernel void surface_fill(const int odd, global const real* f, global uchar* type, global const ushort* element,
                         global const real* wall_u, global real* fill, global acc* mass, global const char* convert,
                         global uchar* change, global acc* excess, global uint* counters) {
    CELL_LOOP_BEGIN
    if (type[k] != INTERFACE || convert[k] <= 0 || change[k] != NONE) continue;
    // the density the cell now holds as fluid: its incoming populations (its gas neighbours have just been
    // given theirs), so that tracked mass and populations stay in step
    acc rho = 0;
    for (int i = 0; i < Q; ++i) rho += (acc)incoming(odd, x, y, z, k, i, f, type, element, wall_u);
    rho += (acc)1;
    excess[k] = mass[k] - rho;
    change[k] = convert[k] == 2 ? ENCLOSED : FILLED;
    atomic_inc(&counters[3]);
    type[k] = FLUID;
    mass[k] = rho;
    fill[k] = 1;
    CELL_LOOP_END
}

#if POCKET_REACH > 0
// A closed gas pocket's deficit taken near it (FluidLattice::set_pocket_reach; the CPU's spread_pocket): the
// wet cells within POCKET_REACH steps of (x0, y0, z0) along the links, the start apart, level by level as
// bits of the box of 2 POCKET_REACH + 1 cells a side around it (private; each cell once: along a periodic
// axis shorter than that, POCKET_FULL_X/Y/Z, the box spans the axis and its bits are the cells' own
// coordinates). From a pocket (`gather` 0): *first the interface cells found (each marked in `near`),
// *second those of them on the other side of the region's face than the pocket. From an interface cell
// (`gather` 1): *first its shares of the deficits of the pockets within reach that take theirs near them
// (their share_total: the receivers they found), in the search's order (the same sums on every run).
#define POCKET_SIDE (2 * POCKET_REACH + 1)
#define POCKET_SX (POCKET_FULL_X ? NX : POCKET_SIDE)
#define POCKET_SY (POCKET_FULL_Y ? NY : POCKET_SIDE)
#define POCKET_SZ (POCKET_FULL_Z ? NZ : POCKET_SIDE)
#define POCKET_BOX (POCKET_SX * POCKET_SY * POCKET_SZ)
#define POCKET_WORDS ((POCKET_BOX + 31) / 32)
// the box's coordinate of the domain's coordinate c on an axis of n cells (start c0, periodic or not, the
// box spanning it or not), and back
inline int box_coordinate(int c, int c0, int n, int periodic, int full) {
    if (full) return c;
    int offset = c - c0;
    if (periodic && offset > POCKET_REACH) offset -= n;
    if (periodic && offset < -POCKET_REACH) offset += n;
    return offset + POCKET_REACH;
}
// c one step beyond an axis of n cells, back on it (periodic)
inline int wrap_axis(int c, int n) { return c < 0 ? c + n : (c >= n ? c - n : c); }
inline int domain_coordinate(int b, int c0, int n, int full) {
    return full ? b : wrap_axis(c0 + b - POCKET_REACH, n);
}
inline void pocket_search(int x0, int y0, int z0, int gather, global const uchar* type, global const uchar* change,
                          global const acc* share_total, global const acc* excess, global const uchar* region,
                          global uchar* near, acc* first, acc* second) {
    uint seen[POCKET_WORDS], front[POCKET_WORDS], next[POCKET_WORDS];
    for (int w = 0; w < POCKET_WORDS; ++w) seen[w] = front[w] = 0u;
    const int start = box_coordinate(x0, x0, NX, PX, POCKET_FULL_X) +
                      POCKET_SX * (box_coordinate(y0, y0, NY, PY, POCKET_FULL_Y) +
                                   POCKET_SY * box_coordinate(z0, z0, NZ, PZ, POCKET_FULL_Z));
    seen[start / 32] = front[start / 32] = 1u << (start % 32);
    const int inside = (region[(long)x0 + (long)ROW * y0 + (long)PLANE * z0] & 1) != 0;
    *first = 0;
    *second = 0;
    for (int level = 0; level < POCKET_REACH; ++level) {
        for (int w = 0; w < POCKET_WORDS; ++w) next[w] = 0u;
        for (int c = 0; c < POCKET_BOX; ++c) {
            if ((front[c / 32] & (1u << (c % 32))) == 0u) continue;
            const int x = domain_coordinate(c % POCKET_SX, x0, NX, POCKET_FULL_X),
                      y = domain_coordinate(c / POCKET_SX % POCKET_SY, y0, NY, POCKET_FULL_Y),
                      z = domain_coordinate(c / (POCKET_SX * POCKET_SY), z0, NZ, POCKET_FULL_Z);
            for (int i = 1; i < Q; ++i) {
                const long n = neighbour(x, y, z, i, 1);
                if (n < 0) continue;
                const int e = box_coordinate(wrap_axis(x + CX[i], NX), x0, NX, PX, POCKET_FULL_X) +
                              POCKET_SX * (box_coordinate(wrap_axis(y + CY[i], NY), y0, NY, PY, POCKET_FULL_Y) +
                                           POCKET_SY * box_coordinate(wrap_axis(z + CZ[i], NZ), z0, NZ, PZ,
                                                                      POCKET_FULL_Z));
                if ((seen[e / 32] & (1u << (e % 32))) != 0u) continue;
                const uchar t = type[n];
                if (t != FLUID && t != INTERFACE) continue;
                seen[e / 32] |= 1u << (e % 32);
                next[e / 32] |= 1u << (e % 32);
                if (gather) {
                    if (change[n] == ENCLOSED && share_total[n] > (acc)0) *first += excess[n] / share_total[n];
                } else if (t == INTERFACE) {
                    near[n] = 1;  // (every writer writes 1)
                    *first += (acc)1;
                    if (((region[n] & 1) != 0) != inside) *second += (acc)1;
                }
            }
        }
        for (int w = 0; w < POCKET_WORDS; ++w) front[w] = next[w];
    }
}
#endif

// A converted cell's weights toward its interface neighbours, max(0, ±n·c_i) (+ filled, − emptied): their
// total into share_total (−1: uniform over share_count neighbours); with none, or a closed gas pocket's
// volume, its excess is an orphan, spread over the whole surface — with POCKET_REACH, a closed pocket's is
// the interface cells' within reach (their count into share_total, each marked in pocket_near for
// surface_gather) if it finds any. Every converted cell writes its orphan (0 if none) and the share of its
// excess its neighbours across the region's face take (into the region +, out of it −: region_excess); the
// others' are not read.
kernel void surface_shares(global const uchar* type, global const uchar* change, global const real* normal,
                           global const acc* excess, global acc* share_total, global uchar* share_count,
                           global acc* orphan, global uint* counters, global const uchar* outlet,
                           global const uchar* region, global acc* region_excess, global uchar* pocket_near) {
    CELL_LOOP_BEGIN
    const uchar c = change[k];
    if (c != FILLED && c != EMPTIED && c != ENCLOSED) continue;  // (sum_orphans reads these cells' alone)
    acc lost = 0;
    region_excess[k] = 0;
    if (c == EMPTIED && outlet[k] != 0) {
        // drained through its outlet (sum_orphans adds it to the outlet's tally, not to the surface)
        share_count[k] = 0;
        orphan[k] = excess[k];
        continue;
    }
    if (c == FILLED || c == EMPTIED) {
        const real sign = c == FILLED ? (real)1 : (real)-1;
        acc total = 0;
        int count = 0;
        for (int i = 1; i < Q; ++i) {
            const long n = neighbour(x, y, z, i, 1);
            if (n < 0 || type[n] != INTERFACE) continue;
            const real w = sign * (normal[3 * k] * (real)CX[i] + normal[3 * k + 1] * (real)CY[i] +
                                   normal[3 * k + 2] * (real)CZ[i]);
            total += (acc)fmax(w, (real)0);
            ++count;
        }
        share_total[k] = total;
        share_count[k] = (uchar)count;
        if (count == 0) lost = excess[k];
        // the shares surface_gather hands across the region's face (RegionBits: region_downstream)
        const int inside = (region[k] & 1) != 0;
        acc across = 0;
        for (int i = 1; i < Q && count > 0; ++i) {
            const long n = neighbour(x, y, z, i, 1);
            if (n < 0 || type[n] != INTERFACE || ((region[n] & 1) != 0) == inside) continue;
            const real w = sign * (normal[3 * k] * (real)CX[i] + normal[3 * k + 1] * (real)CY[i] +
                                   normal[3 * k + 2] * (real)CZ[i]);
            const acc share = total > (acc)0 ? (acc)fmax(w, (real)0) / total : (acc)1 / (acc)count;
            across += share * excess[k];
        }
        region_excess[k] = inside ? -across : across;
    } else if (c == ENCLOSED) {
        lost = excess[k];
#if POCKET_REACH > 0
        acc receivers, across;
        pocket_search(x, y, z, 0, type, change, share_total, excess, region, pocket_near, &receivers, &across);
        share_total[k] = receivers;
        if (receivers > (acc)0) {
            lost = 0;
            const acc share = excess[k] / receivers;
            region_excess[k] = (region[k] & 1) != 0 ? -across * share : across * share;
            atomic_inc(&counters[6]);
        }
#endif
    }
    if (lost != (acc)0) atomic_inc(&counters[5]);  // (an outlet's drained cells returned above)
    orphan[k] = lost;
    CELL_LOOP_END
}

// Each interface cell's shares of its converted neighbours' excess, and with POCKET_REACH, where
// surface_shares marked it, of the pockets' deficits near it (the mark cleared for the next step).
kernel void surface_gather(global const uchar* type, global const uchar* change, global const real* normal,
                           global const acc* excess, global const acc* share_total,
                           global const uchar* share_count, global acc* mass, global const uchar* region,
                           global uchar* pocket_near) {
    CELL_LOOP_BEGIN
    if (type[k] != INTERFACE) continue;
    acc gained = 0;
    for (int j = 1; j < Q; ++j) {
        const long q = neighbour(x, y, z, j, 1);
        if (q < 0) continue;
        const uchar c = change[q];
        if ((c != FILLED && c != EMPTIED) || share_count[q] == 0) continue;
        // q sees this cell along c_i = −c_j
        const int i = OPPOSITE(j);
        const real sign = c == FILLED ? (real)1 : (real)-1;
        const real w = fmax(sign * (normal[3 * q] * (real)CX[i] + normal[3 * q + 1] * (real)CY[i] +
                                    normal[3 * q + 2] * (real)CZ[i]),
                            (real)0);
        const acc total = share_total[q];
        const acc share = total > (acc)0 ? (acc)w / total : (acc)1 / (acc)share_count[q];
        gained += share * excess[q];
    }
#if POCKET_REACH > 0
    if (pocket_near[k] != 0) {
        pocket_near[k] = 0;
        acc nearby, unused;
        pocket_search(x, y, z, 1, type, change, share_total, excess, region, pocket_near, &nearby, &unused);
        gained += nearby;
    }
#endif
    mass[k] += gained;
    CELL_LOOP_END
}

// The orphans' total, the mass drained through each outlet and the interface cells' count, and of these the
// region's (its orphans, its interface cells: FluidLattice::region_inflow's spreads): work-item g of the fixed
// grid sums the cells g, g + G, g + 2G, … in order, the work-group a tree (SUMS values: the orphans, one per
// outlet, the region's orphans, the excess handed into the region; two counts); spread_orphans (one
// work-group) sums the groups' in the same way, leaves the share per interface cell in share[0], adds the
// drained mass to the outlets' tallies and what the conversions brought the region to its inflow.
#define SUMS (3 + MAX_OUTLETS)
#define REGION_ORPHANS (1 + MAX_OUTLETS)
#define REGION_EXCESS (2 + MAX_OUTLETS)
// The work-group's sums of its items' s[0..SUMS) and c[0..2) as a tree, the same order every time: into
// partial[0..SUMS) and count[0..2).
inline void group_sum(const acc* s, const uint* c, local acc* partial, local uint* count) {
    const int l = get_local_id(0), n = get_local_size(0);
    for (int a = 0; a < SUMS; ++a) partial[SUMS * l + a] = s[a];
    count[2 * l] = c[0];
    count[2 * l + 1] = c[1];
    for (int span = n / 2; span > 0; span /= 2) {
        barrier(CLK_LOCAL_MEM_FENCE);
        if (l < span) {
            for (int a = 0; a < SUMS; ++a) partial[SUMS * l + a] += partial[SUMS * (l + span) + a];
            count[2 * l] += count[2 * (l + span)];
            count[2 * l + 1] += count[2 * (l + span) + 1];
        }
    }
    barrier(CLK_LOCAL_MEM_FENCE);
}

kernel void sum_orphans(global const acc* orphan, global const uchar* type, global const uchar* outlet,
                        global const uchar* change, global const uchar* region, global const acc* region_excess,
                        global acc* group_total, global uint* group_count, local acc* partial,
                        local uint* count) {
    const int l = get_local_id(0);
    const long g = get_global_id(0), stride = get_global_size(0);
    acc s[SUMS];
    for (int a = 0; a < SUMS; ++a) s[a] = 0;
    uint c[2] = {0u, 0u};  // interface cells, of them in the region
    for (long k = g; k < CELLS; k += stride) {
        // a slab's: its own planes' (a ghost's orphans and interface cells are its owner's)
        const int x = (int)(k % ROW);
        if (x < OWN_BEGIN || x >= OWN_END) continue;
        const uchar converted = change[k];
        const int in_region = (region[k] & 1) != 0;  // (RegionBits: region_downstream)
        if (converted == FILLED || converted == EMPTIED || converted == ENCLOSED) {
            s[outlet[k]] += orphan[k];  // outlet 0: none, the orphans; o + 1: outlet o
            if (outlet[k] == 0 && in_region) s[REGION_ORPHANS] += orphan[k];
            s[REGION_EXCESS] += region_excess[k];
        }
        const uint surface = type[k] == INTERFACE ? 1u : 0u;
        c[0] += surface;
        c[1] += in_region ? surface : 0u;
    }
    group_sum(s, c, partial, count);
    if (l == 0) {
        for (int a = 0; a < SUMS; ++a) group_total[SUMS * get_group_id(0) + a] = partial[a];
        group_count[2 * get_group_id(0)] = count[0];
        group_count[2 * get_group_id(0) + 1] = count[1];
    }
}

kernel void spread_orphans(const int groups, global const acc* group_total, global const uint* group_count,
                           global acc* share, global acc* drained, global acc* region_inflow,
                           local acc* partial, local uint* count) {
    const int l = get_local_id(0), n = get_local_size(0);
    acc s[SUMS];
    for (int a = 0; a < SUMS; ++a) s[a] = 0;
    uint c[2] = {0u, 0u};
    for (int g = l; g < groups; g += n) {
        for (int a = 0; a < SUMS; ++a) s[a] += group_total[SUMS * g + a];
        c[0] += group_count[2 * g];
        c[1] += group_count[2 * g + 1];
    }
    group_sum(s, c, partial, count);
    if (l == 0) {
#if DIVIDED
        // this slab's totals: the host sums the orphans and interface cells over the slabs, writes the share
        // and adds the region's inflow
        share[0] = partial[0];
        share[1] = (acc)count[0];
        share[2] = partial[REGION_ORPHANS];
        share[3] = (acc)count[1];
        region_inflow[2] += partial[REGION_EXCESS];
#else
        const int spread = partial[0] != (acc)0 && count[0] > 0u;
        share[0] = spread ? partial[0] / (acc)count[0] : (acc)0;
        region_inflow[2] += partial[REGION_EXCESS];
        if (spread) region_inflow[2] += share[0] * (acc)count[1] - partial[REGION_ORPHANS];
#endif
        for (int o = 0; o < MAX_OUTLETS; ++o) drained[o] += partial[1 + o];
    }
}

// The mass each link into the region (FluidLattice::set_region) carried in the step just done, as the CPU's
// count_crossings() counts it, into mass[g]: link g from cell from[g] along c_direction[g] to cell to[g].
kernel void count_crossings(const int odd, global const real* f, global const uchar* type,
                            global const ushort* element, global const real* wall_u, global const real* fill,
                            global const uint* from, global const uint* to, global const uchar* direction,
                            const uint count, global acc* mass) {
    const uint g = get_global_id(0);
    if (g >= count) return;
    const long a = from[g], b = to[g];
    const uchar ta = type[a], tb = type[b];
    acc m = 0;
    if ((ta == FLUID || ta == INTERFACE) && (tb == FLUID || tb == INTERFACE)) {  // else nothing crosses
        const int i = direction[g];
        const acc alpha = ta == INTERFACE && tb == INTERFACE ? (acc)0.5 * ((acc)fill[a] + (acc)fill[b]) : (acc)1;
        const int xa = (int)(a % ROW), ya = (int)((a / ROW) % NY), za = (int)(a / PLANE);
        const int xb = (int)(b % ROW), yb = (int)((b / ROW) % NY), zb = (int)(b / PLANE);
        // (the rest weights of f_i and f_ī cancel)
        m = alpha * ((acc)incoming(odd, xb, yb, zb, b, i, f, type, element, wall_u) -
                     (acc)incoming(odd, xa, ya, za, a, OPPOSITE(i), f, type, element, wall_u));
    }
    mass[g] = m;
}

// The links' masses summed per part by one work-group, the same order every time, added to inflow[0..2).
kernel void sum_crossings(const uint count, global const acc* mass, global const uchar* part,
                          global acc* inflow, local acc* partial) {
    const int l = get_local_id(0), n = get_local_size(0);
    acc s[2] = {0, 0};
    for (uint g = l; g < count; g += n) s[part[g]] += mass[g];
    partial[2 * l] = s[0];
    partial[2 * l + 1] = s[1];
    for (int span = n / 2; span > 0; span /= 2) {
        barrier(CLK_LOCAL_MEM_FENCE);
        if (l < span) {
            partial[2 * l] += partial[2 * (l + span)];
            partial[2 * l + 1] += partial[2 * (l + span) + 1];
        }
    }
    if (l == 0) {
        inflow[0] += partial[0];
        inflow[1] += partial[1];
    }
}

kernel void surface_finish(global const uchar* type, global acc* mass, global real* fill, global const acc* srho,
                           global const acc* share) {
    CELL_LOOP_BEGIN
    if (type[k] != INTERFACE) continue;
    const acc m = mass[k] + share[0];
    mass[k] = m;
    fill[k] = (real)(m / srho[k]);
    CELL_LOOP_END
}

// The inflow boundary's held cells (lbm/inlet.h: the CPU's hold_inlet()): cell[g] held at density rho[g]
// (top[g]: on the held layers' top) moving at u; the mass each adds into added[g]. A fluid cell is put at
// equilibrium in the layout of the parity (its arriving populations: after an odd count in its neighbours'
// slots; the obstacles next to the inlet are at rest), an interface cell filled; gas waits.
kernel void hold_inlet_cells(const int odd, global real* f, global const uchar* type, global const ushort* element,
                             global const real* wall_u, global real* fill, global acc* mass, global const acc* srho,
                             global const uint* cell, global const acc* rho, global const uchar* top,
                             const uint count, const real ux, const real uy, const real uz, global acc* added) {
    const uint g = get_global_id(0);
    if (g >= count) return;
    const long k = cell[g];
    const int x = (int)(k % ROW), y = (int)((k / ROW) % NY), z = (int)(k / PLANE);
    acc gained = 0;
    if (type[k] == FLUID) {
        acc here = 1;  // ρ of its arriving populations (the rest weights sum to 1)
        for (int i = 0; i < Q; ++i) here += (acc)incoming(odd, x, y, z, k, i, f, type, element, wall_u);
        gained = rho[g] - here;
        mass[k] = rho[g];
        fill[k] = 1;
        const real r = (real)rho[g], u2 = (real)1.5 * (ux * ux + uy * uy + uz * uz);
        for (int i = 0; i < Q; ++i) {
            const real cu = (real)CX[i] * ux + (real)CY[i] * uy + (real)CZ[i] * uz;
            const real v = WEIGHT(i) * (r * ((real)1 + (real)3 * cu + (real)4.5 * cu * cu - u2) - (real)1);
            const long src = odd ? neighbour(x, y, z, i, -1) : -1;
            if (!odd || src < 0 || type[src] == OBSTACLE)
                f[i * (long)SLOT + k] = v;  // its own slot i (after an odd count: what a wall returns there)
            else
                f[OPPOSITE(i) * (long)SLOT + src] = v;
        }
    } else if (type[k] == INTERFACE) {
        const acc here = srho[k];  // its last collision's ρ, of its fill fraction
        const acc target = (top[g] ? (acc)1 : (acc)1 + (acc)2 * (acc)SURFACE_EPSILON) * here;
        if (target > mass[k]) {
            gained = target - mass[k];
            mass[k] = target;
            fill[k] = (real)(target / here);
        }
    }
    added[g] = gained;
}

kernel void surface_prepare(const int odd, global const real* f, global const uchar* type,
                            global const ushort* element, global const real* wall_u, global const real* fill,
                            global uchar* out_known, global real* out, global real* normal) {
    CELL_LOOP_BEGIN
    if (type[k] != INTERFACE) continue;
    if (out_known[k] == 0) {
        for (int i = 0; i < Q; ++i) out[i * (long)CELLS + k] = outgoing(odd, x, y, z, k, i, f, type, element, wall_u);
        out_known[k] = 1;
    }
    real n[3];
    surface_normal(x, y, z, k, type, fill, n);
    for (int a = 0; a < 3; ++a) normal[3 * k + a] = n[a];
    CELL_LOOP_END
}

#endif
