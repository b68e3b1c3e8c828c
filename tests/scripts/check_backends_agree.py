#!/usr/bin/env python3
"""Two runs of one case on the two lattice backends (CPU, OpenCL) agree: every series.csv column, row by
row, to float64 round-off (relative 1e-9 with an absolute floor of 1e-12 for values that are round-off
themselves, such as the mass drift), the same number of rows, and the summary's status.

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
    for i, (ra, rb) in enumerate(zip(a, b)):
        for key in ra:
            x, y = float(ra[key]), float(rb[key])
            excess = abs(x - y) / (RELATIVE * max(abs(x), abs(y)) + ABSOLUTE)
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
