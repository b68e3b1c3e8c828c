#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks a fluid-only C5 run against the slit barrier (the debris case, V_s = 0) for what must hold
whatever the resolution:
- it reached its end time, and the lattice kept its mass (relative drift <= 1e-10);
- causality: the barrier feels no fluid force before the front has reached its face (within 2 cells);
- the front is never ahead of the frictionless bound x0 + 2 sqrt(g h cos(theta)) t + g sin(theta) t^2 / 2
  (Ritter's dam-break front on the slope, block length x0, height h): a cell that outruns it has been
  accelerated by the numerics (the spray drops that free-fell without bound did, session 7);
- the fluid reached the barrier and part of it passed the slit (0 < non-retained < 1);
- an open channel (channel_top "open"): what left through the outlets is accounted for — the series'
  fluid_left_domain_fraction ends at the summary's three fractions' sum, never falls, and some fluid left
  through the outflow (the front reaches it); the non-retained fraction counts it. Under a lid none leaves.
Usage: check_c5_fluid_run.py DIR"""
import csv
import json
import math
import os
import sys
import tomllib

folder = sys.argv[1]
s = json.load(open(os.path.join(folder, "summary.json")))
case = tomllib.load(open(os.path.join(folder, "case_resolved.toml"), "rb"))
rows = list(csv.DictReader(open(os.path.join(folder, "series.csv"))))
g = case["channel"]["gravity_m_s2"]
theta = math.radians(case["channel"]["slope_deg"])
x0, h = case["debris"]["block_length_m"], case["debris"]["block_height_m"]
face, dx = case["barrier"]["face_x_m"], s["dx_m"]
w_sin = s["W_sin_theta_N"]

bad = []
if s["status"] != "completed":
    bad.append(f"status {s['status']}: {s['failure']}")
if s["max_relative_mass_drift"] > 1e-10:
    bad.append(f"mass drift {s['max_relative_mass_drift']:.2e}")
first_force = next((float(r["time_s"]) for r in rows if abs(float(r["fluid_force_normal_N"])) > 0.01 * w_sin), None)
arrival = next((float(r["time_s"]) for r in rows if float(r["front_x_m"]) >= face - 2 * dx), None)
print(f"front at the barrier (within 2 cells) at {arrival} s; first fluid force above 1 % of W sin(theta) at "
      f"{first_force} s; peak normal {s['fluid_force_normal_max_over_W_sin_theta']:.3f} W sin(theta) at "
      f"{s['time_of_fluid_force_normal_max_s']} s; non-retained {s['fluid_non_retained_fraction']:.4f}")
if first_force is None or arrival is None:
    bad.append("the fluid never loaded the barrier")
elif first_force < arrival:
    bad.append(f"fluid force at {first_force} s before the front reached the barrier ({arrival} s)")
worst = -math.inf
for r in rows[1:]:
    t = float(r["time_s"])
    bound = x0 + 2.0 * math.sqrt(g * h * math.cos(theta)) * t + 0.5 * g * math.sin(theta) * t * t
    front = float(r["front_x_m"])
    worst = max(worst, front - bound)
    if front > bound + dx:
        bad.append(f"front {front:.3f} m at t = {t} s ahead of the frictionless bound {bound:.3f} m")
        break
print(f"front minus the frictionless bound after t = 0: at most {worst:+.3f} m")
if not 0.0 < s["fluid_non_retained_fraction"] < 1.0:
    bad.append(f"non-retained fraction {s['fluid_non_retained_fraction']} (fluid must pass the slit, not all)")
left = [float(r["fluid_left_domain_fraction"]) for r in rows]
parts = [s[f"fluid_left_{o}_fraction"] for o in ("end", "sides", "top")]
print(f"channel top {s['channel_top']}: left through the outflow, sides, top {parts}")
if any(b < a for a, b in zip(left, left[1:])):
    bad.append("the fluid that left the domain decreased")
if abs(left[-1] - sum(parts)) > 1e-6:
    bad.append(f"the series' fluid_left_domain_fraction ends at {left[-1]}, the summary's parts sum to {sum(parts)}")
if s["channel_top"] == "open":
    if not parts[0] > 0.0:
        bad.append("no fluid left through the outflow of an open channel")
    if not s["fluid_non_retained_fraction"] >= parts[0]:
        bad.append("the non-retained fraction does not count what left through the outflow")
elif sum(parts) != 0.0:
    bad.append(f"fluid left a closed box: {parts}")
if bad:
    sys.exit("; ".join(bad))
print("C5 fluid run checks passed")
