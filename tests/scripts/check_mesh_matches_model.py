#!/usr/bin/env python3
"""A barrier from a mesh of the box model's piles gives the box model's results (and a concave part, the
results of the same shape in convex parts).

    check_mesh_matches_model.py BOX_RUN MESH_RUN

The mesh's walls touch the grains as the boxes do, to round-off (tests/dem/mesh_wall_test.cpp), so the two
runs follow each other until the round-off grows in the collisions, and end as two realisations of one
flow. Asserts: the series equal to 9 digits up to the first impact on the barrier (its force still zero in
both), the non-retained fraction within 0.01, the force at the end within 5 %, the peak within 15 % (a peak is
one collision), the same clogging mechanism. Prints "mesh matches the model: …" or the differences, exit 1.
"""
import csv
import json
import os
import sys


def load(run):
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    with open(os.path.join(run, "series.csv"), encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    return summary, rows


def rows_agree(rows_a, rows_b, stop, what):
    """The rows of two series compared from the first until stop(row of b): every column within 1e-7 of the
    larger value (or of 1: J, N). Returns how many were compared and each differing row's first difference."""
    compared, problems = 0, []
    for ra, rb in zip(rows_a, rows_b):
        if stop(rb):
            break
        compared += 1
        for key in rb:
            x, y = float(ra[key]), float(rb[key])
            if abs(x - y) > 1e-7 * max(abs(x), abs(y), 1.0):
                problems.append(f"{what}, row {compared}: {key} {x} vs {y}")
                break
    return compared, problems


def within_realisations(summary, others, keys, name):
    """Each of the summary's `keys` within twice the range of the other runs' values (realisations of one flow)
    of their mean. Returns the problems and a phrase per key."""
    problems, said = [], []
    for key in keys:
        values = [o[key] for o, _ in others]
        mean, spread = sum(values) / len(values), max(values) - min(values)
        if abs(summary[key] - mean) > 2.0 * spread:
            problems.append(f"{key}: {summary[key]:.6g} against the {name} runs' {min(values):.6g}…{max(values):.6g}")
        said.append(f"{key} {summary[key]:.4g} ({name} {min(values):.4g}…{max(values):.4g})")
    return problems, said


def main():
    (a, rows_a), (b, rows_b) = load(sys.argv[1]), load(sys.argv[2])
    problems = []
    force = "barrier_force_resultant_N"
    before = 0
    for ra, rb in zip(rows_a, rows_b):
        if float(ra[force]) != 0.0 or float(rb[force]) != 0.0:
            break
        before += 1
        for key in ra:
            x, y = float(ra[key]), float(rb[key])
            if abs(x - y) > 1e-9 * max(abs(x), abs(y), 1e-30):
                problems.append(f"before the impact, row {before}: {key} {x} vs {y}")
                break
    if before == 0:
        problems.append("no row before the impact")

    def close(key, tolerance, relative=True):
        x, y = a[key], b[key]
        diff = abs(x - y) / max(abs(x), 1e-30) if relative else abs(x - y)
        if diff > tolerance:
            problems.append(f"{key}: {x} (boxes) vs {y} (mesh)")
        return f"{key} {x:.4g}/{y:.4g}"

    said = [close("non_retained_fraction", 0.01, relative=False), close("end_global_force_N", 0.05),
            close("max_global_force_N", 0.15)]
    if a["clogging_mechanism"] != b["clogging_mechanism"]:
        problems.append(f"clogging: {a['clogging_mechanism']} vs {b['clogging_mechanism']}")
    if problems:
        print("\n".join(problems[:10]))
        return 1
    print(f"mesh matches the model: {before} rows equal before the impact; " + ", ".join(said) +
          f"; {a['clogging_mechanism']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
