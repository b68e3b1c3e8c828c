#!/usr/bin/env python3
"""What entered the region behind a barrier is what passed it, over the crest, through the outlets, or moved
there by the free surface's conversions.

    check_fluid_overflow.py RUN closed|slit

A fluid-only debris run whose channel holds no fluid behind the barrier at the start. The fluid that entered
the region behind the barrier's downstream face (summary.json: fluid_over_crest_fraction +
fluid_through_outlets_fraction + fluid_spread_behind_fraction) is what is there now or left through the
channel's end (fluid_non_retained_fraction), plus what left the region over the side walls or through the
domain's top: so it lies between the non-retained fraction and that plus fluid_left_sides_fraction +
fluid_left_top_fraction, to round-off (1e-9). Also: a closed barrier lets nothing through and most of what
passed went over it; a slit barrier lets most through; the conversions' share lies in [-0.02, passed] (a
closed pocket near the region's face takes its volume from the surface cells on both sides of it when the
pockets' volume is taken near them, lattice.pocket_reach_cells ≥ 1: measured −0.008 of the fluid at
dx = 5 cm and −0.003 at 2.5 cm on the slit case; taken from the whole surface, it is ≥ 0); the
series' last fluid_over_crest_fraction is the summary's. Prints "fluid overflow ok: …" or the
differences, exit 1.
"""
import csv
import json
import os
import sys


def main():
    run, kind = sys.argv[1], sys.argv[2]
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        s = json.load(f)
    with open(os.path.join(run, "series.csv"), encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    over, through = s["fluid_over_crest_fraction"], s["fluid_through_outlets_fraction"]
    spread, passed = s["fluid_spread_behind_fraction"], s["fluid_non_retained_fraction"]
    left_elsewhere = s["fluid_left_sides_fraction"] + s["fluid_left_top_fraction"]
    entered = over + through + spread
    problems = []
    if not passed - 1e-9 <= entered <= passed + left_elsewhere + 1e-9:
        problems.append(f"entered {entered:.9f} (over {over:.9f} + through {through:.9f} + spread {spread:.9f}) "
                        f"outside [passed {passed:.9f}, + left over the sides and top {left_elsewhere:.9f}]")
    if passed < 0.1:
        problems.append(f"only {passed:.4f} passed: the run tests nothing")
    if not -0.02 <= spread <= passed:
        problems.append(f"the conversions' share {spread} outside [-0.02, {passed}]")
    if kind == "closed" and (through != 0.0 or over < 0.5 * passed):
        problems.append(f"a closed barrier: {through} through it, {over} over it of {passed}")
    if kind == "slit" and through < 0.5 * passed:
        problems.append(f"a slit barrier: only {through} through it of {passed}")
    if abs(float(rows[-1]["fluid_over_crest_fraction"]) - over) > 1e-9:
        problems.append(f"series' last fluid_over_crest_fraction {rows[-1]['fluid_over_crest_fraction']} vs {over}")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"fluid overflow ok: passed {passed:.4f}; entered {entered:.4f} = over the crest {over:.4f} + through "
          f"the outlets {through:.4f} + the surface's conversions {spread:.4f}; left over the sides and top "
          f"{left_elsewhere:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
