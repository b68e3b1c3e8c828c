#!/usr/bin/env python3
"""A mesh barrier's force maps on its triangles (barrier_facets.vtp) add up to its parts' maps.

    check_facet_maps.py [--with-fluid] RUN_DIR TRIANGLES

barrier_facets.vtp holds, per triangle, the grains' contact force at the times of the barrier's force maps
(t1, t2, t3, end; docs/geometry.md, "Force maps on the mesh"). The triangles of part p carry the contacts of
the barrier's element p (a grains-only run: its whole load), so at every map their forces sum to the
element's row in barrier_maps.csv — written to 9 digits, so within 1e-8 of the map's largest element force.
The map at the grains' own peak (grains_peak) has no element map: its triangles' forces along the barrier
face's normal sum to the summary's largest normal force of the grains. With --with-fluid (grains in a
fluid) the element maps hold the fluid's load too: the triangles' sums are not compared with them. Asserts these sums, TRIANGLES triangles, each triangle's pressure as its force pressing on its outer face over
its area, and that the largest global force's map (t3) is not empty. Prints "facet maps ok: …" or the
differences, exit 1.
"""
import csv
import json
import math
import os
import sys

from check_geometry import read_vtp

MAPS = ("t1", "t2", "t3", "end")  # the element maps' times; and the grains' own peak:
PEAK = "grains_peak"


def main():
    args = sys.argv[1:]
    with_fluid = "--with-fluid" in args
    if with_fluid:
        args.remove("--with-fluid")
    run, triangles = args[0], int(args[1])
    polys, a = read_vtp(os.path.join(run, "barrier_facets.vtp"))
    problems = []
    if polys != triangles:
        problems.append(f"{polys} triangles, {triangles} expected")
    with open(os.path.join(run, "barrier_maps.csv"), encoding="utf-8") as f:
        elements = [r for r in csv.DictReader(f) if not r["element"].startswith("#")]
    points, conn = a["points"], a["connectivity"]
    for m in MAPS + (PEAK,):
        force, pressure = a[f"grain_force_{m}_N"], a[f"grain_pressure_{m}_Pa"]
        rows = [[float(r[f"{m}_f{c}_N"]) for c in "xyz"] for r in elements] if m != PEAK else []
        scale = max([math.sqrt(sum(v * v for v in f)) for f in rows + force] + [1e-30])
        for e, row in enumerate(rows):
            total = [sum(force[t][c] for t in range(polys) if int(a["part"][t]) == e) for c in range(3)]
            if not with_fluid and any(abs(total[c] - row[c]) > 1e-8 * scale for c in range(3)):
                problems.append(f"map {m}, part {e}: the triangles sum to {total}, the element's map is {row}")
        for t in range(polys):
            p0, p1, p2 = (points[conn[3 * t + k]] for k in range(3))
            u = [p1[c] - p0[c] for c in range(3)]
            v = [p2[c] - p0[c] for c in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            area = 0.5 * math.sqrt(sum(c * c for c in n))
            if abs(area - a["area_m2"][t]) > 1e-9 * max(area, 1e-12):
                problems.append(f"triangle {t}: area {a['area_m2'][t]} of {area} m2")
            expected = -sum(force[t][c] * n[c] for c in range(3)) / (2.0 * area) / area
            if abs(pressure[t] - expected) > 1e-9 * max(abs(expected), 1e-9 * scale / area):
                problems.append(f"map {m}, triangle {t}: pressure {pressure[t]} Pa, its force gives {expected}")
        if m == "t3" and scale <= 1e-30 and not with_fluid:
            problems.append("the largest global force's map is empty")
    # the grains' peak: their force along the face's normal, summed over the triangles, is the largest normal
    # force of the grains the summary reports (a channel run's max_normal_force_N, a debris run's
    # solid_force_normal_max_N)
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    normal = summary["barrier_face_normal"]
    peak = summary.get("solid_force_normal_max_N", summary.get("max_normal_force_N"))
    along = sum(sum(a[f"grain_force_{PEAK}_N"][t][c] * normal[c] for c in range(3)) for t in range(polys))
    if not peak or abs(along - peak) > 1e-8 * abs(peak):  # (the summary's 9 digits)
        problems.append(f"the grains' peak map: {along} N along the face's normal, the summary's peak {peak} N")
    if problems:
        print("differences:\n  " + "\n  ".join(problems[:20]))
        return 1
    loaded = sum(1 for t in range(polys) if any(abs(c) > 0 for c in a["grain_force_t3_N"][t]))
    sums = "the grains' peak checked" if with_fluid else "every map's triangles sum to their part's"
    print(f"facet maps ok: {polys} triangles in {len(elements)} parts, {loaded} loaded at t3, {sums}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
