// SPDX-License-Identifier: MIT
// The state of a few whole planes of a slab, packed into one contiguous message and back (a run divided
// among MPI ranks, docs/scaling.md: the ghost planes staged through the host). A cell's state is what a
// step reads of it: the populations and τ, and with a free surface its type, λ, m and the interface
// state of its last collision (ρ, u, normal, outgoing populations). Cells in image order within each
// array: x fastest over the `planes` planes from x0, then y, then z. Follows stream_collide (its types).
#define PLANE_CELL_BEGIN                                                       \
    const int i = get_global_id(0), y = get_global_id(1), z = get_global_id(2); \
    if (i >= planes) return;                                                   \
    const long k = (long)(x0 + i) + (long)ROW * y + (long)PLANE * z;           \
    const long c = (long)i + (long)planes * (y + (long)NY * z), n = (long)planes * NY * NZ;

#if FREE_SURFACE
#define PLANE_SURFACE_PARAMS                                                                               \
    , global uchar *type, global real *fill, global acc *mass, global acc *srho, global real *su,          \
        global real *normal, global real *out, global uchar *out_known, global acc *wide, global uchar *bytes
#else
#define PLANE_SURFACE_PARAMS
#endif

// The cells of planes [x0, x0 + planes) into reals (the populations, τ; then λ, u, normal and the outgoing
// populations), wide (m, ρ) and bytes (type, out_known).
kernel void pack_planes(const int x0, const int planes, global const real* f, global const real* tau,
                        global real* reals PLANE_SURFACE_PARAMS) {
    PLANE_CELL_BEGIN
    for (int q = 0; q < Q; ++q) reals[q * n + c] = f[q * (long)SLOT + k];
    reals[Q * n + c] = tau[k];
#if FREE_SURFACE
    reals[(Q + 1) * n + c] = fill[k];
    for (int a = 0; a < 3; ++a) {
        reals[(Q + 2 + a) * n + c] = su[3 * k + a];
        reals[(Q + 5 + a) * n + c] = normal[3 * k + a];
    }
    for (int q = 0; q < Q; ++q) reals[(Q + 8 + q) * n + c] = out[q * (long)CELLS + k];
    wide[c] = mass[k];
    wide[n + c] = srho[k];
    bytes[c] = type[k];
    bytes[n + c] = out_known[k];
#endif
}

kernel void unpack_planes(const int x0, const int planes, global real* f, global real* tau,
                          global const real* reals PLANE_SURFACE_PARAMS) {
    PLANE_CELL_BEGIN
    for (int q = 0; q < Q; ++q) f[q * (long)SLOT + k] = reals[q * n + c];
    tau[k] = reals[Q * n + c];
#if FREE_SURFACE
    fill[k] = reals[(Q + 1) * n + c];
    for (int a = 0; a < 3; ++a) {
        su[3 * k + a] = reals[(Q + 2 + a) * n + c];
        normal[3 * k + a] = reals[(Q + 5 + a) * n + c];
    }
    for (int q = 0; q < Q; ++q) out[q * (long)CELLS + k] = reals[(Q + 8 + q) * n + c];
    mass[k] = wide[c];
    srho[k] = wide[n + c];
    type[k] = bytes[c];
    out_known[k] = bytes[n + c];
#endif
}
