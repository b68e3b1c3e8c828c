#!/usr/bin/env python3
"""Grains fed from a hydrograph enter as it says, and the gauge downstream measures them.

    check_inflow.py RUN DISCHARGE_M3_S SOLID_FRACTION FROM_S

Asserts: the inserted solid volume equals the hydrograph's integral up to the last batch within 1 %
(summary.json, and inflow.csv's last row the same), inflow.csv's volumes never decrease; the gauge's solid
discharge (the grains' flux through its section) averaged from FROM_S to the end — a steady flow by then —
equals DISCHARGE_M3_S x SOLID_FRACTION within 5 % (the batches enter as pulses a few tenths of a second
apart: the mean over many of them is the flux). Prints "inflow ok: ..." or the differences, exit 1.
"""
import csv
import json
import os
import sys


def main():
    run, q, c, start = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        s = json.load(f)
    with open(os.path.join(run, "inflow.csv"), encoding="utf-8") as f:
        batches = list(csv.DictReader(f))
    with open(os.path.join(run, "gauge.csv"), encoding="utf-8") as f:
        gauge = [r for r in csv.DictReader(f) if float(r["time_s"]) >= start]
    problems = []
    due, entered = s["inflow_hydrograph_solid_volume_m3"], s["inflow_solid_volume_m3"]
    if due <= 0.0 or abs(entered - due) > 0.01 * due:
        problems.append(f"entered {entered} m3 of the hydrograph's {due} m3")
    if abs(float(batches[-1]["inflow_solid_volume_m3"]) - entered) > 1e-9 * entered:
        problems.append("inflow.csv's last row is not the summary's")
    volumes = [float(b["inflow_solid_volume_m3"]) for b in batches]
    if any(b < a for a, b in zip(volumes, volumes[1:])):
        problems.append("the inserted volume decreased")
    if len(gauge) < 20:
        problems.append(f"{len(gauge)} gauge rows after {start} s")
    else:
        mean = sum(float(r["solid_discharge_m3_s"]) for r in gauge) / len(gauge)
        if abs(mean - q * c) > 0.05 * q * c:
            problems.append(f"the gauge measured {mean:.4f} m3/s of grains, the hydrograph feeds {q * c:.4f}")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"inflow ok: {entered:.4f} of {due:.4f} m3 entered in {len(batches)} batches "
          f"({s['inflow_grains']} grains); the gauge measured {mean:.4f} m3/s of grains, fed {q * c:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
