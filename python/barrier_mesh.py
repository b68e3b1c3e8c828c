#!/usr/bin/env python3
"""Barrier and channel meshes as STL files (ASCII, one solid per part) for `barrier.type = "mesh"` and
`channel.mesh_file` (docs/geometry.md).

    barrier_mesh.py boxes OUT.stl FACE_X THICKNESS HEIGHT Y0:Y1 [Y0:Y1 ...]
        one box per pile, its face at x = FACE_X, THICKNESS along x, HEIGHT above the bed, across y from Y0
        to Y1 (metres): the box model's piles as a mesh
        --footing LENGTH:HEIGHT  each pile stands on a footing that reaches LENGTH upstream of the face,
        HEIGHT high: one solid with an inner edge where pile and footing meet (a concave part); with
        --split-footing the footing is a part of its own (the same shape in two convex parts)
    barrier_mesh.py slit-dam OUT.stl [--width 2.1] [--face-x 8.0] [--height 1.35] [--slit 0.3]
        a slit dam as built in the field: two piles whose sides taper from the foundation to the crest
        (0.45 m thick at the base, 0.3 m at the crest, their crest sloping down toward the slit), a wing
        wall on each bank rising 0.3 m above the crest, and a foundation sill across the whole channel,
        0.15 m high, reaching 0.6 m downstream of the face (an apron)
    barrier_mesh.py channel-walls OUT.stl [--length 20] [--width 2.3] [--height 1.35] [--thickness 0.1]
                                  [--taper X0:X1:W]
        the two side walls of a channel whose domain is --width wide: slabs --thickness thick along its
        sides (the flow between them --width − 2 --thickness wide), as high as --height; with --taper the
        flow's width narrows linearly from X0 to X1 to W (m), both walls alike, and stays W downstream
        (each wall three convex parts: straight, tapering, straight)

    barrier_mesh.py bed OUT.stl X0:X1 HEIGHT [--width 2.1] [--ramp LENGTH]
        relief on the channel's bed (a sill, a step, an apron): one part named bed_sill, across the whole
        width, its top HEIGHT above the bed from X0 to X1; with --ramp its ends slope down to the bed over
        LENGTH beyond X0 and X1 (parts named bed… are the bed's, not side walls, in channel.mesh_file)

    --refine N (any of them)
        each triangle split into four at its edges' midpoints, N times (4^N as many triangles, the same
        shape): a model as finely meshed as a CAD export, for testing and timing

Triangles run counter-clockwise seen from outside; every part is a closed surface.
"""
import argparse
import sys


def hexahedron(corners):
    """The 12 triangles of a six-faced solid given its 8 corners in the order
    (x0 y0 z0), (x1 y0 z0), (x0 y1 z0), (x1 y1 z0), (x0 y0 z1), (x1 y0 z1), (x0 y1 z1), (x1 y1 z1)
    (any hexahedron whose faces are planar enough: a box sheared or tapered)."""
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = []
    for a, b, c, d in faces:
        tris.append((corners[a], corners[b], corners[c]))
        tris.append((corners[a], corners[c], corners[d]))
    return tris


def box(x0, x1, y0, y1, z0, z1):
    return hexahedron([(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)])


def extruded(profile, y0, y1):
    """The solid swept by the polygon `profile` (x, z corners, counter-clockwise with x to the right and z
    up; convex or not) from y = y0 to y1: its sides as quads, its ends cut into triangles by ear clipping."""
    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def inside(p, a, b, c):
        return cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0

    ears, left = [], list(range(len(profile)))
    while len(left) > 3:
        for k in range(len(left)):
            i, j, m = left[k - 1], left[k], left[(k + 1) % len(left)]
            a, b, c = profile[i], profile[j], profile[m]
            if cross(a, b, c) <= 0:
                continue  # a reflex corner
            if any(inside(profile[q], a, b, c) for q in left if q not in (i, j, m)):
                continue
            ears.append((i, j, m))
            left.pop(k)
            break
        else:
            raise ValueError("the profile is not a simple counter-clockwise polygon")
    ears.append(tuple(left))
    low = [(x, y0, z) for x, z in profile]
    high = [(x, y1, z) for x, z in profile]
    tris = []
    for i, j, m in ears:  # x × z = −y: counter-clockwise in (x, z) faces −y at y0
        tris.append((low[i], low[j], low[m]))
        tris.append((high[i], high[m], high[j]))
    n = len(profile)
    for i in range(n):
        j = (i + 1) % n
        tris.append((low[i], high[i], high[j]))
        tris.append((low[i], high[j], low[j]))
    return tris


def refined(tris, levels):
    """Each triangle as four, `levels` times; a shared edge's midpoint is the same for both its triangles
    (the same arithmetic on the same ends), so a closed part stays closed."""
    def mid(p, q):
        return tuple(0.5 * (a + b) for a, b in zip(p, q))
    for _ in range(levels):
        tris = [t for a, b, c in tris
                for t in ((a, mid(a, b), mid(c, a)), (mid(a, b), b, mid(b, c)), (mid(c, a), mid(b, c), c),
                          (mid(a, b), mid(b, c), mid(c, a)))]
    return tris


def solid(name, tris):
    lines = [f"solid {name}"]
    for t in tris:
        lines.append("  facet normal 0 0 0\n    outer loop")
        lines += [f"      vertex {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}" for p in t]
        lines.append("    endloop\n  endfacet")
    lines.append(f"endsolid {name}")
    return "\n".join(lines) + "\n"


def slit_dam(width, face_x, height, slit):
    base_t, crest_t = 0.45, 0.30
    y_lo, y_hi = 0.5 * (width - slit), 0.5 * (width + slit)
    parts = []
    for name, (ya, yb) in (("pile_left", (0.0, y_lo)), ("pile_right", (y_hi, width))):
        # thicker at the base (the downstream face leans), the crest 0.1 m lower at the slit side
        inner = yb if name == "pile_left" else ya
        corners = []
        for z in (0.0, 1.0):
            for y in (ya, yb):
                for x in (0.0, 1.0):
                    t = base_t if z == 0.0 else crest_t
                    zz = 0.0 if z == 0.0 else (height - 0.1 if y == inner else height)
                    corners.append((face_x + x * t, y, zz))
        parts.append((name, hexahedron(corners)))
    wing = 0.15
    parts.append(("wing_left", box(face_x, face_x + base_t, 0.0, wing, height, height + 0.3)))
    parts.append(("wing_right", box(face_x, face_x + base_t, width - wing, width, height, height + 0.3)))
    parts.append(("sill", box(face_x - 0.15, face_x + 0.6, 0.0, width, 0.0, 0.15)))
    return parts


def channel_walls(length, width, height, thickness, taper):
    """Side-wall slabs; inner faces at y = thickness and width − thickness, moved in by the taper."""
    wide = width - 2.0 * thickness
    if taper is None:
        spans = [(0.0, length, wide, wide)]
    else:
        x0, x1, narrow = taper
        spans = [(0.0, x0, wide, wide), (x0, x1, wide, narrow), (x1, length, narrow, narrow)]
    parts = []
    for k, (xa, xb, wa, wb) in enumerate(spans):
        if xb <= xa:
            continue
        ia, ib = 0.5 * (width - wa), 0.5 * (width - wb)  # the inner faces' distance from the domain's sides
        for side in ("left", "right"):
            corners = []
            for z in (0.0, height):
                for outer in (True, False):  # y0: the outer face, y1: the inner face
                    for x, inner in ((xa, ia), (xb, ib)):
                        y = (0.0 if outer else inner) if side == "left" else (width - inner if not outer else width)
                        corners.append((x, y, z))
            if side == "right":  # keep y0 < y1: the inner face first
                corners = [corners[i] for i in (2, 3, 0, 1, 6, 7, 4, 5)]
            parts.append((f"wall_{side}_{k}", hexahedron(corners)))
    return parts


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="kind", required=True)
    b = sub.add_parser("boxes")
    b.add_argument("out")
    b.add_argument("face_x", type=float)
    b.add_argument("thickness", type=float)
    b.add_argument("height", type=float)
    b.add_argument("spans", nargs="+")
    b.add_argument("--footing")
    b.add_argument("--split-footing", action="store_true")
    s = sub.add_parser("slit-dam")
    s.add_argument("out")
    s.add_argument("--width", type=float, default=2.1)
    s.add_argument("--face-x", type=float, default=8.0)
    s.add_argument("--height", type=float, default=1.35)
    s.add_argument("--slit", type=float, default=0.3)
    w = sub.add_parser("channel-walls")
    w.add_argument("out")
    w.add_argument("--length", type=float, default=20.0)
    w.add_argument("--width", type=float, default=2.3)
    w.add_argument("--height", type=float, default=1.35)
    w.add_argument("--thickness", type=float, default=0.1)
    w.add_argument("--taper")
    d = sub.add_parser("bed")
    d.add_argument("out")
    d.add_argument("span")
    d.add_argument("height", type=float)
    d.add_argument("--width", type=float, default=2.1)
    d.add_argument("--ramp", type=float, default=0.0)
    for parser in (b, s, w, d):
        parser.add_argument("--refine", type=int, default=0)
    a = p.parse_args()
    if a.kind == "channel-walls":
        taper = tuple(float(v) for v in a.taper.split(":")) if a.taper else None
        parts = channel_walls(a.length, a.width, a.height, a.thickness, taper)
    elif a.kind == "bed":
        x0, x1 = (float(v) for v in a.span.split(":"))
        profile = [(x0 - a.ramp, 0.0), (x1 + a.ramp, 0.0), (x1, a.height), (x0, a.height)]
        parts = [("bed_sill", extruded(profile, 0.0, a.width))]
    elif a.kind == "boxes":
        parts = []
        length, high = (float(v) for v in a.footing.split(":")) if a.footing else (0.0, 0.0)
        x0, x1 = a.face_x, a.face_x + a.thickness
        for k, span in enumerate(a.spans):
            y0, y1 = (float(v) for v in span.split(":"))
            if not a.footing:
                parts.append((f"pile_{k}", box(x0, x1, y0, y1, 0.0, a.height)))
            elif a.split_footing:
                parts.append((f"pile_{k}", box(x0, x1, y0, y1, high, a.height)))
                parts.append((f"footing_{k}", box(x0 - length, x1, y0, y1, 0.0, high)))
            else:  # the L of pile and footing, in x–z
                profile = [(x0 - length, 0.0), (x1, 0.0), (x1, a.height), (x0, a.height), (x0, high),
                           (x0 - length, high)]
                parts.append((f"pile_{k}", extruded(profile, y0, y1)))
    else:
        parts = slit_dam(a.width, a.face_x, a.height, a.slit)
    parts = [(name, refined(tris, a.refine)) for name, tris in parts]
    with open(a.out, "w", encoding="utf-8") as f:
        for name, tris in parts:
            f.write(solid(name, tris))
    print(f"{a.out}: {len(parts)} parts, {sum(len(t) for _, t in parts)} triangles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
