#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks a finished run's gauge and design outputs (docs/design.md) for consistency.

    check_design_outputs.py OUT_DIR

The front velocity is the gauge distance over the gauge-to-barrier travel time; the gauge's reading at the
approach time lies between the gauge.csv rows around it; the back-calculated coefficients follow from
design_inputs; design_comparison.csv and report.md carry the comparison.
"""
import csv
import json
import math
import os
import sys


def fail(msg):
    sys.exit(f"check_design_outputs: {msg}")


def main():
    out = sys.argv[1]
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    with open(os.path.join(out, "gauge.csv"), newline="") as f:
        gauge = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    if len(gauge) < 10:
        fail(f"gauge.csv has {len(gauge)} rows")
    t_g, t1, v_f = s["front_arrival_at_gauge_s"], s["approach_impact_time_s"], s["approach_front_velocity_m_s"]
    if not (0.0 < t_g < t1):
        fail(f"front arrival at the gauge {t_g} s not before the first impact {t1} s")
    if abs(v_f - s["gauge_distance_m"] / (t1 - t_g)) > 1e-6 * v_f:
        fail(f"front velocity {v_f} is not distance / (t1 - t_g)")
    t_s = s["approach_time_at_gauge_s"]
    if abs(t_s - (s["approach_peak_time_s"] - s["gauge_distance_m"] / v_f)) > 1e-6:
        fail("approach time is not t_peak - distance / v_f")
    before = [r for r in gauge if r["time_s"] <= t_s][-1]
    after = [r for r in gauge if r["time_s"] >= t_s][0]
    for key, col in (("approach_flow_depth_m", "depth_m"), ("approach_velocity_m_s", "velocity_m_s")):
        lo, hi = sorted((before[col], after[col]))
        if not (lo - 1e-9 <= s[key] <= hi + 1e-9):
            fail(f"{key} = {s[key]} outside the gauge rows around t_s: [{lo}, {hi}]")
    d = s["design_inputs"]
    h, v, rho, w = d["approach_flow_depth_m"], d["approach_velocity_m_s"], d["approach_bulk_density_kg_m3"], d["barrier_width_m"]
    if not (h > 0 and v > 0 and rho > 0):
        fail(f"the approaching flow was not measured: h {h}, v {v}, rho {rho}")
    k_dyn = d["peak_normal_force_N"] / (rho * v * v * h * w)
    if abs(k_dyn - s["k_hydrodynamic"]) > 1e-6 * k_dyn:
        fail(f"k_hydrodynamic {s['k_hydrodynamic']} != F / (rho v^2 h W) = {k_dyn}")
    k_st = d["peak_normal_force_N"] / (0.5 * rho * 9.81 * h * h * w)
    if abs(k_st - s["k_hydrostatic"]) > 1e-6 * k_st:
        fail(f"k_hydrostatic {s['k_hydrostatic']} != {k_st}")
    with open(os.path.join(out, "design_comparison.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    groups = {r["group"] for r in rows}
    for g in ("impact", "boulder", "back-calculated", "typology"):
        if g not in groups:
            fail(f"design_comparison.csv has no {g} rows")
    armanini = next(r for r in rows if r["reference"].startswith("Armanini"))
    expected = 0.5 * 5.0 * rho * 9.81 * h * h * w / 1000.0
    if abs(float(armanini["predicted_low"]) - expected) > 1e-4 * expected:
        fail(f"Armanini's force {armanini['predicted_low']} kN != {expected} kN")
    if os.path.exists(os.path.join(out, "report.md")):
        with open(os.path.join(out, "report.md")) as f:
            if "Beside the design formulas" not in f.read():
                fail("report.md has no design section")
    print(f"ok: v_f = {v_f:.3f} m/s, h = {h:.3f} m, v = {v:.3f} m/s, k_hydrodynamic = {k_dyn:.3f}")


if __name__ == "__main__":
    main()
