#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Asserts that the angle of repose in a calibration sweep folder grows with μ_s at every μ_r and with
μ_r at every μ_s (reference case C1; issue 4's scaled-down sandpile test). Usage: check_calibration_trend.py DIR"""
import csv
import os
import sys

rows = list(csv.DictReader(open(os.path.join(sys.argv[1], "calibration_points.csv"))))
angle = {(float(r["mu_s"]), float(r["mu_r"])): float(r["angle_deg"]) for r in rows}
mu_s = sorted({k[0] for k in angle})
mu_r = sorted({k[1] for k in angle})
assert len(angle) == len(mu_s) * len(mu_r) >= 4, f"incomplete grid: {angle}"
bad = []
for r in mu_r:
    seq = [angle[(s, r)] for s in mu_s]
    if any(b <= a for a, b in zip(seq, seq[1:])):
        bad.append(f"mu_r = {r}: angle vs mu_s {seq}")
for s in mu_s:
    seq = [angle[(s, r)] for r in mu_r]
    if any(b <= a for a, b in zip(seq, seq[1:])):
        bad.append(f"mu_s = {s}: angle vs mu_r {seq}")
for k, v in sorted(angle.items()):
    print(f"mu_s = {k[0]}, mu_r = {k[1]}: {v:.2f} deg")
if bad:
    sys.exit("angle does not grow: " + "; ".join(bad))
print("angle grows with mu_s and mu_r")
