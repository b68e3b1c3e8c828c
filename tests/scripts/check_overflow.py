#!/usr/bin/env python3
"""What passed a barrier is what crossed it, over the crest or through the outlets.

    check_overflow.py RUN TOLERANCE [closed]

In a channel with an open end, a grain past the barrier is either still in the channel downstream of it or
has left at the end; either way it crossed the barrier's thickness once, above the crest (overtopping) or
below it (through the outlets). Asserts: solid_over_crest_fraction + solid_through_outlets_fraction equals
non_retained_fraction within TOLERANCE (the grains that sit inside the barrier's thickness at the end have
crossed part of it, and the time integral is exact to one step's share per grain), something passed and
something left at the end, the series' last over-crest value is the summary's, and for a closed barrier
nothing went through. Prints "overflow ok: …" or the differences, exit 1.
"""
import csv
import json
import os
import sys


def main():
    run, tolerance = sys.argv[1], float(sys.argv[2])
    closed = len(sys.argv) > 3 and sys.argv[3] == "closed"
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        s = json.load(f)
    with open(os.path.join(run, "series.csv"), encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    passed, over, through = s["non_retained_fraction"], s["solid_over_crest_fraction"], s["solid_through_outlets_fraction"]
    problems = []
    if abs(over + through - passed) > tolerance:
        problems.append(f"over the crest {over:.6f} + through the outlets {through:.6f} != passed {passed:.6f}")
    if passed < 0.05:
        problems.append(f"only {passed:.4f} passed: the run tests nothing")
    if s["grains_left_end"] < 1 or s["solid_left_end_fraction"] <= 0.0 or s["solid_left_end_fraction"] > passed:
        problems.append(f"left at the end: {s['grains_left_end']} grains, {s['solid_left_end_fraction']}")
    if s["channel_end"] != "open":
        problems.append(f"channel_end {s['channel_end']}")
    if closed and through != 0.0:
        problems.append(f"{through} through a closed barrier")
    if closed and over < 0.05:
        problems.append(f"only {over} over the crest of a closed barrier")
    if abs(float(rows[-1]["over_crest_fraction"]) - over) > 1e-9:
        problems.append(f"series' last over_crest_fraction {rows[-1]['over_crest_fraction']} vs {over}")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"overflow ok: passed {passed:.4f} = over the crest {over:.4f} + through the outlets {through:.4f}; "
          f"left at the end {s['solid_left_end_fraction']:.4f} ({s['grains_left_end']} grains)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
