#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Asserts the fluid's load on a closed barrier at rest (a level channel, the debris case): the normal
force, averaged over the last 3 s of the series, equals the hydrostatic thrust ½ ρ g h² W with
h = V / (L W) the depth of the fluid spread between the upstream wall and the barrier face (L = the
face's X), within 5 % (the face lies on a cell boundary; the fluid still sloshes by ~2 %; interface
cells round the depth). Checks the momentum-exchange force in newtons, its gauge reference (the
atmosphere on the dry side), and the barrier cells. Usage: check_fluid_barrier_load.py DIR"""
import csv
import json
import os
import sys

folder = sys.argv[1]
s = json.load(open(os.path.join(folder, "summary.json")))
rows = list(csv.DictReader(open(os.path.join(folder, "series.csv"))))
t_end = float(rows[-1]["time_s"])
late = [float(r["fluid_force_normal_N"]) for r in rows if float(r["time_s"]) >= t_end - 3.0]
force = sum(late) / len(late)
rho = 1500.0 if "density" not in s else s["density"]
width, length = s["channel_width_m"], s["barrier_face_x_m"]
depth = s["fluid_volume_m3"] / (length * width)
expected = 0.5 * rho * 9.81 * depth ** 2 * width
print(f"depth {depth:.4f} m; fluid normal force {force:.1f} N (mean of the last 3 s) vs hydrostatic {expected:.1f} N "
      f"({100 * (force / expected - 1):+.2f} %); non-retained {s['fluid_non_retained_fraction']:.4f}")
bad = []
if s["status"] != "completed":
    bad.append(f"status {s['status']}")
if abs(force / expected - 1.0) > 0.05:
    bad.append("the load differs from the hydrostatic thrust by more than 5 %")
if s["fluid_non_retained_fraction"] > 1e-6:
    bad.append("fluid passed a closed barrier")
if s["max_relative_mass_drift"] > 1e-10:
    bad.append(f"mass drift {s['max_relative_mass_drift']:.2e}")
if bad:
    sys.exit("; ".join(bad))
print("fluid barrier load checks passed")
