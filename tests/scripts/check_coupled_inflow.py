#!/usr/bin/env python3
"""Grains and fluid fed together from one hydrograph enter as it says, and the flow carries the grains.

    check_coupled_inflow.py RUN FLUID_M3 SOLID_M3

FLUID_M3 and SOLID_M3: the hydrograph's integrals of Q (1 - c) and Q c over the run (computed by hand from the
test's file). Asserts: the summary's hydrograph volumes are these (1e-9: the split of the discharge between
the lattice's inflow and the grains'), what entered of each is within 1 % of them, inflow.csv (the fluid) and
inflow_grains.csv (the grains) end at the summary's values, and the gauge downstream of the inflow zone saw
grains pass (solid discharge > 0 in some row: the fluid carried them). Prints "coupled inflow ok: ..." or
the differences, exit 1.
"""
import csv
import json
import os
import sys


def last_row(path):
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(f))[-1]


def main():
    run, fluid, solid = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        s = json.load(f)
    problems = []
    for key, expected in (("inflow_hydrograph_volume_m3", fluid), ("inflow_hydrograph_solid_volume_m3", solid)):
        if abs(s[key] - expected) > 1e-9 * expected:
            problems.append(f"{key} {s[key]} where the hydrograph gives {expected}")
    for key, expected in (("inflow_volume_m3", fluid), ("inflow_solid_volume_m3", solid)):
        if abs(s[key] - expected) > 0.01 * expected:
            problems.append(f"{key}: {s[key]} entered of {expected} m3")
    if abs(float(last_row(os.path.join(run, "inflow.csv"))["inflow_volume_m3"]) - s["inflow_volume_m3"]) > 1e-9:
        problems.append("inflow.csv's last row is not the summary's")
    grains = last_row(os.path.join(run, "inflow_grains.csv"))
    if abs(float(grains["inflow_solid_volume_m3"]) - s["inflow_solid_volume_m3"]) > 1e-12:
        problems.append("inflow_grains.csv's last row is not the summary's")
    with open(os.path.join(run, "gauge.csv"), encoding="utf-8") as f:
        passing = [float(r["solid_discharge_m3_s"]) for r in csv.DictReader(f)]
    if max(passing, default=0.0) <= 0.0:
        problems.append("no grain passed the gauge")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"coupled inflow ok: {s['inflow_volume_m3']:.5f} of {fluid:.5f} m3 of fluid and "
          f"{s['inflow_solid_volume_m3']:.5f} of {solid:.5f} m3 of grains ({s['inflow_grains']} grains) entered; "
          f"the gauge saw up to {max(passing):.4f} m3/s of grains pass")
    return 0


if __name__ == "__main__":
    sys.exit(main())
