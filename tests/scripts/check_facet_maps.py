#!/usr/bin/env python3
"""A mesh barrier's force maps on its triangles (barrier_facets.vtp) add up to its parts' maps.

    check_facet_maps.py RUN_DIR TRIANGLES [--against OTHER_RUN RELATIVE]

barrier_facets.vtp holds, per triangle, the grains' contact force and the fluid's momentum exchange (each
if the run has it) at the times of the barrier's force maps (t1, t2, t3, end; docs/geometry.md, "Force maps
on the mesh"). The triangles of part p carry the loads of the barrier's element p, so at every map their
forces, grains' and fluid's together, sum to the element's row in barrier_maps.csv — written to 9 digits,
so within 1e-8 of the map's largest element force. The maps at the grains' and the fluid's own peaks
(grains_peak, fluid_peak) have no element map: their triangles' forces along the barrier face's normal sum
to the summary's largest normal force of the grains, of the fluid. Asserts these sums, TRIANGLES triangles,
each triangle's pressures (each component's force pressing on its outer face over its area; with both
components, their sum) and that the largest global force's map (t3) is not empty. With --against: every
triangle's forces within RELATIVE of each map's largest of OTHER_RUN's (the same case on another backend or
number of ranks). Prints "facet maps ok: …" or the differences, exit 1.
"""
import csv
import json
import math
import os
import sys

from check_geometry import read_vtp

MAPS = ("t1", "t2", "t3", "end")  # the element maps' times; and each component's own peak:
PEAKS = {"grain": ("grains_peak", ("solid_force_normal_max_N", "max_normal_force_N")),
         "fluid": ("fluid_peak", ("fluid_force_normal_max_N",))}


def outward_area(points, conn, t):
    """Twice the area along the outward normal, and the area."""
    p0, p1, p2 = (points[conn[3 * t + k]] for k in range(3))
    u = [p1[c] - p0[c] for c in range(3)]
    v = [p2[c] - p0[c] for c in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    return n, 0.5 * math.sqrt(sum(c * c for c in n))


def main():
    run, triangles = sys.argv[1], int(sys.argv[2])
    polys, a = read_vtp(os.path.join(run, "barrier_facets.vtp"))
    problems = []
    against = sys.argv[sys.argv.index("--against") + 1:] if "--against" in sys.argv else None
    if against:
        other = read_vtp(os.path.join(against[0], "barrier_facets.vtp"))[1]
        relative = float(against[1])
        worst = 0.0
        for name in (n for n in a if "_force_" in n):
            largest = max(abs(v) for f in other[name] for v in f)
            diff = max(abs(f[c] - g[c]) for f, g in zip(a[name], other[name]) for c in range(3))
            worst = max(worst, diff / largest if largest > 0 else diff)
            if diff > relative * largest:
                problems.append(f"{name}: {diff} N from {against[0]}'s (its largest {largest} N)")
    if polys != triangles:
        problems.append(f"{polys} triangles, {triangles} expected")
    components = [c for c in ("grain", "fluid") if f"{c}_force_t1_N" in a]
    if not components:
        problems.append("neither the grains' nor the fluid's forces in barrier_facets.vtp")
    with open(os.path.join(run, "barrier_maps.csv"), encoding="utf-8") as f:
        elements = [r for r in csv.DictReader(f) if not r["element"].startswith("#")]
    points, conn = a["points"], a["connectivity"]
    normals = [outward_area(points, conn, t) for t in range(polys)]
    for t in range(polys):
        if abs(normals[t][1] - a["area_m2"][t]) > 1e-9 * max(normals[t][1], 1e-12):
            problems.append(f"triangle {t}: area {a['area_m2'][t]} of {normals[t][1]} m2")
    maps = list(MAPS) + [PEAKS[c][0] for c in components]
    for m in maps:
        force = {c: a[f"{c}_force_{m}_N"] for c in components}
        rows = [[float(r[f"{m}_f{x}_N"]) for x in "xyz"] for r in elements] if m in MAPS else []
        scale = max([math.sqrt(sum(v * v for v in f)) for f in rows] +
                    [math.sqrt(sum(v * v for v in f[t])) for f in force.values() for t in range(polys)] + [1e-30])
        for e, row in enumerate(rows):
            total = [sum(f[t][x] for f in force.values() for t in range(polys) if int(a["part"][t]) == e)
                     for x in range(3)]
            if any(abs(total[x] - row[x]) > 1e-8 * scale for x in range(3)):
                problems.append(f"map {m}, part {e}: the triangles sum to {total}, the element's map is {row}")
        for t in range(polys):
            n, area = normals[t]
            summed = 0.0
            for c, f in force.items():
                expected = -sum(f[t][x] * n[x] for x in range(3)) / (2.0 * area) / area
                summed += expected
                got = a[f"{c}_pressure_{m}_Pa"][t]
                if abs(got - expected) > 1e-9 * max(abs(expected), 1e-9 * scale / area):
                    problems.append(f"map {m}, triangle {t}: {c} pressure {got} Pa, its force gives {expected}")
            if len(components) == 2 and abs(a[f"pressure_{m}_Pa"][t] - summed) > 1e-9 * max(abs(summed), 1e-9 * scale / area):
                problems.append(f"map {m}, triangle {t}: pressure {a[f'pressure_{m}_Pa'][t]} Pa, the components' {summed}")
        if m == "t3" and scale <= 1e-30:
            problems.append("the largest global force's map is empty")
    # each component's peak: its force along the face's normal, summed over the triangles, is the summary's
    # largest normal force of that component (a channel run's max_normal_force_N, a debris run's
    # solid_force_normal_max_N and fluid_force_normal_max_N)
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    normal = summary["barrier_face_normal"]
    for c in components:
        name, keys = PEAKS[c]
        peak = next((summary[k] for k in keys if summary.get(k) is not None), None)
        along = sum(sum(a[f"{c}_force_{name}_N"][t][x] * normal[x] for x in range(3)) for t in range(polys))
        if not peak or abs(along - peak) > 1e-8 * abs(peak):  # (the summary's 9 digits)
            problems.append(f"the {name} map: {along} N along the face's normal, the summary's peak {peak} N")
    if problems:
        print("differences:\n  " + "\n  ".join(problems[:20]))
        return 1
    loaded = sum(1 for t in range(polys)
                 if any(abs(x) > 0 for c in components for x in a[f"{c}_force_t3_N"][t]))
    print(f"facet maps ok: {polys} triangles in {len(elements)} parts, {loaded} loaded at t3, "
          f"the {' and '.join(components)} forces of every map summing to their part's"
          + (f", within {worst:.1e} of {against[0]}'s" if against else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
