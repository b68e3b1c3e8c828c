#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks a fluid-box run of one sphere (cases/settling_sphere.toml) for what must hold:
- it completed and the lattice kept its mass (relative drift <= 1e-10);
- the buoyancy in grains_series.csv is the sphere's exact rho_f g V at every row after the start (the
  sphere stays under the surface of a full box); with partially saturated cells (coupling_model "psm") the
  exchange carries the pressure on the solid share of the grain's cells and the buoyancy term the rest: there
  it lies between 0 and rho_f g V;
- a sinking sphere (denser than the fluid): terminal over the run's last fifth (its mean within 1 % of the
  mean over the fifth before), forces balanced there (drag + buoyancy = its weight within 2 %), and the
  settling velocity within BAND of Schiller & Naumann's with Di Felice's wall factor for the box's width:
  the simplified immersed boundary at d/dx = 8 settles that much fast, converging with d/dx
  (docs/results/settling.md);
- a neutrally buoyant sphere (--neutral): it moves at less than 5 % of the speed the same sphere twice as
  dense settles at in this box (what is left is the drag a held sphere still feels, 3.7 % of Archimedes'
  force at d/dx 8.6: docs/coupling.md).
Usage: check_settling_sphere.py DIR [--neutral] [--band LOW HIGH]"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python"))
from settling_study import schiller_naumann  # noqa: E402

folder = sys.argv[1]
neutral = "--neutral" in sys.argv
band = (1.0, 1.25)
if "--band" in sys.argv:
    k = sys.argv.index("--band")
    band = (float(sys.argv[k + 1]), float(sys.argv[k + 2]))
s = json.load(open(os.path.join(folder, "summary.json")))
rows = list(csv.DictReader(open(os.path.join(folder, "grains_series.csv"))))
grain = s["grain_settling"][0]
r, rho_s, rho_f, eta, g = (grain["radius_m"], s["grain_density_kg_m3"], s["fluid_density_kg_m3"],
                           s["viscosity_Pa_s"], s["gravity_m_s2"])
volume = 4.0 / 3.0 * math.pi * r ** 3
archimedes, weight = rho_f * g * volume, rho_s * g * volume
bad = []
if s["status"] != "completed":
    bad.append(f"status {s['status']}")
if s["max_relative_mass_drift"] > 1e-10:
    bad.append(f"mass drift {s['max_relative_mass_drift']:.2e}")
shares = [float(x["buoyancy_z_N"]) / archimedes for x in rows[1:]]
if s.get("coupling_model") == "psm":
    print(f"buoyancy term over rho_f g V (the share the exchange does not carry): {min(shares):.3f} ... "
          f"{max(shares):.3f}")
    if not all(0.0 <= b <= 1.0 + 1e-12 for b in shares):
        bad.append(f"the buoyancy term leaves [0, rho_f g V]: {min(shares):.3f} ... {max(shares):.3f}")
else:
    worst = max(abs(b - 1.0) for b in shares)
    print(f"buoyancy against rho_f g V: worst relative deviation {worst:.1e}")
    if worst > 1e-9:
        bad.append(f"the buoyancy deviates from rho_f g V by {worst:.2e}")
end = s["simulated_time_s"]
late = [x for x in rows if float(x["time_s"]) >= 0.8 * end - 1e-12]
before = [x for x in rows if 0.6 * end - 1e-12 <= float(x["time_s"]) < 0.8 * end - 1e-12]
mean = lambda xs, key: sum(float(x[key]) for x in xs) / len(xs)  # noqa: E731
v_late, v_before = -mean(late, "vz_m_s"), -mean(before, "vz_m_s")
walls = schiller_naumann(2 * r, rho_s - rho_f, rho_f, eta, g, wall_lambda=2 * r / s["box_width_m"])
if neutral:
    reference = schiller_naumann(2 * r, rho_f, rho_f, eta, g, wall_lambda=2 * r / s["box_width_m"])
    print(f"neutral sphere: {1000 * v_late:.3f} mm/s over the last fifth; twice as dense it would settle at "
          f"{1000 * reference:.2f} mm/s")
    if abs(v_late) > 0.05 * reference:
        bad.append(f"a neutrally buoyant sphere moves at {abs(v_late) / reference:.3f} of the settling speed")
else:
    balance = (mean(late, "drag_z_N") + mean(late, "buoyancy_z_N")) / weight
    print(f"settling {1000 * v_late:.3f} mm/s (the fifth before: {1000 * v_before:.3f}); (drag + buoyancy) / "
          f"weight {balance:.4f}; Schiller-Naumann with the walls {1000 * walls:.3f} mm/s: ratio "
          f"{v_late / walls:.3f} (band {band})")
    if abs(v_late / v_before - 1.0) > 0.01:
        bad.append("not terminal over the last fifth")
    if abs(balance - 1.0) > 0.02:
        bad.append(f"forces not balanced at the terminal velocity: {balance:.4f}")
    if not band[0] <= v_late / walls <= band[1]:
        bad.append(f"settling velocity {v_late / walls:.3f} x the prediction, outside {band}")
if bad:
    sys.exit("; ".join(bad))
print("settling sphere checks passed")
