#!/usr/bin/env python3
"""Two runs of one case on the two lattice backends (CPU, OpenCL) agree: every series.csv column, row by
row, to float64 round-off — within 1e-9 of the largest magnitude among the columns of the same unit (the
name's last part: every force in newtons against the largest force, so a component that is zero up to
round-off, such as the cross-channel force of a symmetric flow, is measured against the forces in play,
not against itself) plus 1e-12 — the same number of rows, and the summary's status.

usage: check_backends_agree.py RUN_A RUN_B
"""
import csv
import json
import sys
from pathlib import Path

RELATIVE, ABSOLUTE = 1e-9, 1e-12


def rows(run):
    with open(Path(run) / "series.csv", newline="") as f:
        return list(csv.DictReader(f))


def main():
    a_dir, b_dir = sys.argv[1], sys.argv[2]
    a, b = rows(a_dir), rows(b_dir)
    if len(a) != len(b) or not a:
        print(f"FAIL: {len(a)} rows against {len(b)}")
        return 1
    worst, where = 0.0, ""
    unit = {key: key.rsplit("_", 1)[-1] for key in a[0]}
    scale = {}
    for key in a[0]:
        largest = max(abs(float(r[key])) for r in a + b)
        scale[unit[key]] = max(scale.get(unit[key], 0.0), largest)
    for i, (ra, rb) in enumerate(zip(a, b)):
        for key in ra:
            x, y = float(ra[key]), float(rb[key])
            excess = abs(x - y) / (RELATIVE * scale[unit[key]] + ABSOLUTE)
            if excess > worst:
                worst, where = excess, f"row {i} {key}: {x!r} vs {y!r}"
    status = [json.load(open(Path(d) / "summary.json"))["status"] for d in (a_dir, b_dir)]
    print(f"{len(a)} rows, {len(a[0])} columns; worst difference {worst:.3g} of the tolerance ({where}); status {status}")
    if worst > 1.0 or status[0] != status[1]:
        print("FAIL")
        return 1
    print("backends agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
