#!/usr/bin/env python3
"""A run against a barrier from a mesh loads each of its parts.

    check_mesh_barrier.py RUN_DIR PARTS

barrier_fluid_elements.csv lists PARTS elements (one per STL solid), each holding lattice cells, and every
part whose centroid lies below the side walls' top loaded at some time (a wing wall above them is reached
only when the flow rises over the walls); summary.json's peak normal force is positive and no series row's normal force exceeds it
(the series is sampled; the peak is taken every step).
Prints "mesh barrier ok: …" or the problems, exit 1.
"""
import csv
import json
import os
import sys
import tomllib


def main():
    run, parts = sys.argv[1], int(sys.argv[2])
    problems = []
    with open(os.path.join(run, "barrier_fluid_elements.csv"), encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    if len(rows) != parts:
        problems.append(f"{len(rows)} elements, expected {parts}")
    with open(os.path.join(run, "case_resolved.toml"), "rb") as f:
        walls = tomllib.load(f)["channel"]["height_m"]
    for r in rows:
        if int(r["lattice_cells"]) <= 0:
            problems.append(f"element {r['element']} holds no lattice cell")
        if float(r["z_m"]) < walls and float(r["max_fluid_force_N"]) <= 0.0:
            problems.append(f"element {r['element']} (its centroid {r['z_m']} m above the bed) never loaded")
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    peak = summary["fluid_force_normal_max_N"]
    with open(os.path.join(run, "series.csv"), encoding="utf-8") as f:
        series = list(csv.DictReader(f))
    column = max(float(r["fluid_force_normal_N"]) for r in series)
    if not (peak > 0.0 and column <= peak * (1 + 1e-12)):
        problems.append(f"summary's peak normal force {peak} N against the series' largest row {column} N")
    if problems:
        print("\n".join(problems))
        return 1
    loads = ", ".join(f"{float(r['max_fluid_force_N']) / 1e3:.1f}" for r in rows)
    print(f"mesh barrier ok: {len(rows)} parts, peak loads {loads} kN, whole barrier {peak / 1e3:.1f} kN")
    return 0


if __name__ == "__main__":
    sys.exit(main())
