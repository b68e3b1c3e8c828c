#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A sandpile divided among MPI ranks gives the results of the run on one process, statistically.

    check_divided_sandpile.py ONE_RANK_DIR SEVERAL_RANKS_DIR RANKS

The divided run adds each grain's contact forces in another order; the settling block then follows the
one-process run to round-off until its grains start to collide in earnest (~0.4 s on the small calibration
pile), and from there a granular flow is another realisation. Checked:
- exact: the grain count, the number of ranks (RANKS); the grain accounting of the divided run (every
  grain left in the run or removed below the plate; some removed);
- series.csv: the kinetic energy at every row up to 0.3 s within 1e-6 of itself (the same trajectory);
- summary.json: the angle of repose within 8 degrees (three standard deviations of its scatter over
  releases of this pile: 2.7 degrees over 30 seeds on one process and on two ranks alike, means 33.48 and
  33.49), the grains on the plate and the heap's height within 10 %, both runs ended by a complete stop.
Prints "statistically the same sandpile on N ranks" or the differences, exit 1.
"""
import csv
import json
import os
import sys


def main():
    one_dir, many_dir, ranks = sys.argv[1], sys.argv[2], int(sys.argv[3])
    one = json.load(open(os.path.join(one_dir, "summary.json")))
    many = json.load(open(os.path.join(many_dir, "summary.json")))
    problems = []
    if many.get("mpi_ranks") != ranks:
        problems.append(f"mpi_ranks: {many.get('mpi_ranks')} (expected {ranks})")
    if one["particles"] != many["particles"]:
        problems.append(f"particles: {one['particles']} vs {many['particles']}")
    left = list(csv.DictReader(open(os.path.join(many_dir, "final_grains.csv"))))
    removed = many["grains_removed_below_plate"]
    if removed <= 0 or len(left) + removed != many["particles"]:
        problems.append(f"grain accounting: {len(left)} left + {removed} removed != {many['particles']}")
    for run, s in (("one process", one), ("divided", many)):
        if s.get("ended_by") != "complete stop":
            problems.append(f"{run}: ended by {s.get('ended_by')!r}, not a complete stop")
    if abs(one["angle_of_repose_deg"] - many["angle_of_repose_deg"]) > 8.0:
        problems.append(f"angle of repose: {one['angle_of_repose_deg']} vs {many['angle_of_repose_deg']}")
    for key in ("grains_on_plate", "heap_height_m"):
        if abs(one[key] - many[key]) > 0.1 * abs(one[key]):
            problems.append(f"{key}: {one[key]} vs {many[key]}")
    rows1 = list(csv.DictReader(open(os.path.join(one_dir, "series.csv"))))
    rows2 = list(csv.DictReader(open(os.path.join(many_dir, "series.csv"))))
    early = 0
    for r1, r2 in zip(rows1, rows2):
        if float(r1["time_s"]) > 0.3:
            break
        early += 1
        a, b = float(r1["kinetic_energy_J"]), float(r2["kinetic_energy_J"])
        if abs(a - b) > 1e-6 * abs(a):
            problems.append(f"series.csv at t = {r1['time_s']}: kinetic energy {a} vs {b}")
            break
    if early < 3:
        problems.append(f"series.csv: only {early} rows before 0.3 s")
    if problems:
        print("differences:\n  " + "\n  ".join(problems))
        return 1
    print(f"statistically the same sandpile on {ranks} ranks (angle {one['angle_of_repose_deg']:.2f} vs "
          f"{many['angle_of_repose_deg']:.2f} deg; {early} series rows equal to 1e-6 before 0.3 s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
