#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks a run of cases/periodic_array_drag.toml (one sphere held in a box periodic every way, the fluid
driven past it along X) for what must hold:
- it completed and the lattice kept its mass (relative drift <= 1e-10); the sphere stayed where it was;
- the flow is steady over the last fifth (the fluid's mean velocity along X within 1e-4 of its value a fifth
  before) and the exchange carries the body force on the box's fluid (within 1e-3 by the cell-centre rule;
  by partially saturated cells less the unweighed solid share, within 5 %);
- the drag over Stokes' at the mean velocity times the array's correction (Hasimoto 1959; Sangani &
  Acrivos 1982) within 10 % of 1 (docs/coupling.md: -8 % at d/dx = 8, tau = 0.8).
Usage: check_periodic_array.py DIR"""
import csv
import json
import os
import sys

folder = sys.argv[1]
s = json.load(open(os.path.join(folder, "summary.json")))
rows = list(csv.DictReader(open(os.path.join(folder, "series.csv"))))
a = s["periodic_array"]
bad = []
if s["status"] != "completed":
    bad.append(f"status {s['status']}")
if s["max_relative_mass_drift"] > 1e-10:
    bad.append(f"mass drift {s['max_relative_mass_drift']:.2e}")
g = s["grain_settling"][0]
if abs(g["x_m"] - 0.0125) > 1e-12 or abs(g["vz_end_m_s"]) > 0.0:
    bad.append(f"the held sphere moved: x = {g['x_m']}, v_z = {g['vz_end_m_s']}")
end = s["simulated_time_s"]
late = [r for r in rows if float(r["time_s"]) >= 0.8 * end - 1e-12]
earlier = [r for r in rows if float(r["time_s"]) <= 0.6 * end + 1e-12]
u_end, u_before = float(late[-1]["fluid_mean_vx_m_s"]), float(earlier[-1]["fluid_mean_vx_m_s"])
carried = a["exchange_force_x_N"] / a["drag_N"]
print(f"mean velocity {1000 * u_end:.5f} mm/s (at {earlier[-1]['time_s']} s: {1000 * u_before:.5f}); "
      f"exchange / body force on the box {carried:.5f}; drag / (Stokes x array correction) "
      f"{a['drag_over_prediction']:.4f} at Re {a['reynolds']:.3f}, solid fraction {a['solid_fraction']:.4f}")
if abs(u_end / u_before - 1.0) > 1e-4:
    bad.append("the flow is not steady")
partial = s.get("coupling_model") == "psm"
if (partial and not 0.95 <= carried <= 1.0 + 1e-9) or (not partial and abs(carried - 1.0) > 1e-3):
    bad.append(f"the exchange carries {carried:.5f} of the body force")
if abs(a["drag_over_prediction"] - 1.0) > 0.10:
    bad.append(f"drag {a['drag_over_prediction']:.4f} x the prediction, beyond 10 %")
if bad:
    sys.exit("; ".join(bad))
print("periodic array checks passed")
