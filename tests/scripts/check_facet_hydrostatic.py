#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The fluid at rest against a meshed wall loads each triangle of its wet face as the hydrostatic pressure
does (barrier_facets.vtp, the end map).

    check_facet_hydrostatic.py RUN_DIR

The run: fluid at rest on a level channel against a closed wall (a mesh box across the channel, its
upstream face at barrier_face_x_m; the debris case's fluid, ρ = 1500 kg/m³). h = V / (L W) is the depth of
the fluid spread between the upstream wall and the face. Each triangle of the face carries the integral of
ρ g (h − z)⁺ over it; the lattice's thrust differs from ½ ρ g h² W by a few per cent (the face on a cell
boundary, the interface cells round the depth, the fluid still sloshes: the run's own test allows 5 %), so
here each triangle's share of the face's load is compared with its hydrostatic share (within 0.01), the
face's load with the thrust (5 %), and every triangle off the face (the dry top and back, the sides against
the channel's walls) carries nothing. Prints "hydrostatic facets ok: …" or the differences, exit 1.
"""
import json
import os
import sys

from check_geometry import read_vtp

RHO, G = 1500.0, 9.81


def hydrostatic(corners, depth, n=200):
    """∫ ρ g (h − z)⁺ dA over a triangle (its corners' y, z), by n² / 2 equal sub-triangles' centroids."""
    (y0, z0), (y1, z1), (y2, z2) = ((p[1], p[2]) for p in corners)
    area = 0.5 * abs((y1 - y0) * (z2 - z0) - (y2 - y0) * (z1 - z0))
    total, count = 0.0, 0
    for i in range(n):
        for j in range(n - i):
            for u, v in (((i + 1 / 3) / n, (j + 1 / 3) / n), ((i + 2 / 3) / n, (j + 2 / 3) / n)):
                if u + v > 1.0:
                    continue
                total += max(depth - (z0 + u * (z1 - z0) + v * (z2 - z0)), 0.0)
                count += 1
    return RHO * G * total / count * area


def main():
    run = sys.argv[1]
    polys, a = read_vtp(os.path.join(run, "barrier_facets.vtp"))
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        s = json.load(f)
    face, width = s["barrier_face_x_m"], s["channel_width_m"]
    depth = s["fluid_volume_m3"] / (face * width)
    points, conn, force = a["points"], a["connectivity"], a["fluid_force_end_N"]
    on_face, problems = [], []
    for t in range(polys):
        corners = [points[conn[3 * t + k]] for k in range(3)]
        if all(abs(p[0] - face) < 1e-9 for p in corners):
            on_face.append((t, force[t][0], hydrostatic(corners, depth)))
        elif any(f != 0.0 for f in force[t]):
            problems.append(f"triangle {t}, off the wet face, carries {force[t]} N")
    load = sum(f for _, f, _ in on_face)
    thrust = sum(h for _, _, h in on_face)
    lines = []
    for t, f, h in on_face:
        lines.append(f"triangle {t}: {f:.1f} N ({f / load:.4f} of the face's), hydrostatic {h:.1f} N ({h / thrust:.4f})")
        if abs(f / load - h / thrust) > 0.01:
            problems.append(lines[-1])
    if abs(load / thrust - 1.0) > 0.05:
        problems.append(f"the face's load {load:.1f} N against the hydrostatic thrust {thrust:.1f} N")
    if len(on_face) < 2:
        problems.append(f"{len(on_face)} triangles on the face at x = {face} m")
    if problems:
        print("differences:\n  " + "\n  ".join(problems))
        return 1
    print(f"hydrostatic facets ok: depth {depth:.4f} m, the face's {len(on_face)} triangles {load:.1f} N against "
          f"{thrust:.1f} N ({100 * (load / thrust - 1):+.2f} %)\n  " + "\n  ".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
