#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks a scaled C5 run with grains (coupled) and its dry twin for what must hold whatever the resolution:
- both completed; the coupled one kept the lattice's mass (relative drift <= 1e-10);
- the series' total normal force is the sum of its solid and fluid parts (to 1e-7 of the peak: the CSV keeps 9 digits);
- causality: no solid force on the barrier before a grain can have reached it (the grains' front starts
  at the block's front and cannot outrun a frictionless slide with the block's drop), no fluid force
  before the fluid front is within 2 cells of the face;
- grains and fluid reached the barrier, and part of each passed the slit (0 < non-retained < 1);
- the dry twin has no fluid (NaN fluid columns, zero fluid force) and the same grains;
- the coupled run's timing: every phase of a coupled step took time, none is negative, the phases
  with "other" add up to the wall time (1e-6 s: the JSON's digits), and the free surface's passes and the
  neighbour lists' builds took time within the lattice's and the grains' phases.
Usage: check_c5_coupled_run.py COUPLED_DIR DRY_DIR"""
import csv
import json
import math
import os
import sys
import tomllib

wet_dir, dry_dir = sys.argv[1], sys.argv[2]


def load(folder):
    s = json.load(open(os.path.join(folder, "summary.json")))
    case = tomllib.load(open(os.path.join(folder, "case_resolved.toml"), "rb"))
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(os.path.join(folder, "series.csv")))]
    return s, case, rows


bad = []
wet, case, rows = load(wet_dir)
dry, _, dry_rows = load(dry_dir)
for name, s in (("coupled", wet), ("dry", dry)):
    if s["status"] != "completed":
        bad.append(f"{name}: status {s['status']}: {s['failure']}")
if wet.get("mode") != "coupled" or dry.get("mode") != "dry":
    bad.append(f"modes {wet.get('mode')}, {dry.get('mode')}")
timing = wet["timing"]
phases = ["lattice_s", "grain_cells_s", "fluid_forces_s", "grains_s", "exchanges_s", "observers_s",
          "checkpoints_s", "other_s"]
parts = {"lattice_free_surface_s": "lattice_s", "grains_neighbour_lists_s": "grains_s"}
exchange_parts = ["exchanges_lattice_s", "exchanges_grains_s", "exchanges_face_moves_s"]  # 0: one process
if sorted(timing) != sorted(phases + ["wall_s"] + list(parts) + exchange_parts):
    bad.append(f"timing keys {sorted(timing)}")
elif any(timing[p] != 0.0 for p in exchange_parts + ["exchanges_s"]):
    bad.append(f"timing: exchanges on one process {timing}")
elif (min(timing[p] for p in phases) < 0.0
      or min(timing[p] for p in ("lattice_s", "grain_cells_s", "fluid_forces_s", "grains_s", "observers_s")) <= 0.0
      or abs(sum(timing[p] for p in phases) - timing["wall_s"]) > 1e-6 * max(1.0, timing["wall_s"])
      or any(not 0.0 < timing[part] <= timing[whole] for part, whole in parts.items())):
    bad.append(f"timing {timing}")
if wet["max_relative_mass_drift"] > 1e-10:
    bad.append(f"mass drift {wet['max_relative_mass_drift']:.2e}")
peak = max(abs(r["force_normal_N"]) for r in rows)
worst = max(abs(r["force_normal_N"] - r["solid_force_normal_N"] - r["fluid_force_normal_N"]) for r in rows)
if worst > 1e-7 * peak:
    bad.append(f"total != solid + fluid by {worst:.3g} N")
g = case["channel"]["gravity_m_s2"]
theta = math.radians(case["channel"]["slope_deg"])
face, dx = case["barrier"]["face_x_m"], wet["dx_m"]
x0, h = case["debris"]["block_length_m"], case["debris"]["block_height_m"]
# a grain can at most slide without friction from the block's front, starting with the speed of a fall
# of the block's height: the earliest time it can touch the face
v0 = math.sqrt(2 * g * h)
a = g * math.sin(theta)
earliest = (-v0 + math.sqrt(v0 * v0 + 2 * a * (face - x0 - 0.2))) / a
first_solid = next((r["time_s"] for r in rows if abs(r["solid_force_normal_N"]) > 1e-6 * peak), None)
first_fluid = next((r["time_s"] for r in rows if abs(r["fluid_force_normal_N"]) > 0.01 * wet["W_tot_sin_theta_N"]), None)
arrival = next((r["time_s"] for r in rows if r["front_x_m"] >= face - 2 * dx), None)
print(f"earliest possible grain contact {earliest:.3f} s; first solid force {first_solid} s; fluid front at the "
      f"face {arrival} s, first fluid force {first_fluid} s; peaks: total "
      f"{wet['force_normal_max_over_W_sin_theta']:.3f}, solid {wet['solid_force_normal_max_over_W_sin_theta']:.3f}, "
      f"fluid {wet['fluid_force_normal_max_over_W_sin_theta']:.3f} W_tot sin(theta); non-retained solid "
      f"{wet['solid_non_retained_fraction']:.4f}, fluid {wet['fluid_non_retained_fraction']:.4f}; dry: peak "
      f"{dry['force_normal_max_over_W_sin_theta']:.3f}, solid non-retained {dry['solid_non_retained_fraction']:.4f}")
if first_solid is None or first_solid < earliest:
    bad.append(f"solid force at {first_solid} s, before a grain can arrive ({earliest:.3f} s)")
if first_fluid is None or arrival is None or first_fluid < arrival - 1e-9:
    bad.append(f"fluid force at {first_fluid} s before the front reached the face ({arrival} s)")
for key in ("solid_non_retained_fraction", "fluid_non_retained_fraction"):
    if not 0.0 < wet[key] < 1.0:
        bad.append(f"{key} = {wet[key]}")
if not 0.0 <= dry["solid_non_retained_fraction"] < 1.0 or dry["grains"] != wet["grains"]:
    bad.append("dry twin: other grains, or all passed")
if any(not math.isnan(r["fluid_non_retained_fraction"]) or r["fluid_force_normal_N"] != 0.0 for r in dry_rows):
    bad.append("dry twin has a fluid")
if bad:
    sys.exit("FAILED: " + "; ".join(bad))
print("ok")
