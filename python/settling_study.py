#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Table of the settling-sphere study (scripts/settling_study.sh): per viscosity and resolution the settling
velocity over the run's last fifth, against Schiller & Naumann's for an unbounded fluid and with Di Felice's
(1996) wall factor for a sphere in a tube of the box's width; per viscosity the observed order of convergence
in dx and the value extrapolated to dx -> 0. Writes OUT/study.csv and prints a markdown table.
Usage: settling_study.py OUT"""
import glob
import json
import math
import os
import sys


def schiller_naumann(d, drho, rho_f, eta, g, wall_lambda=0.0):
    """Terminal velocity with C_D = 24/Re (1 + 0.15 Re^0.687), divided by Di Felice's wall factor
    ((1 - l)/(1 - 0.33 l))^-a, a = (3.3 + 0.085 Re)/(1 + 0.1 Re), at lambda = d/D (0: unbounded)."""
    stokes = drho * g * d * d / (18.0 * eta)
    v = stokes
    for _ in range(500):
        re = v * d * rho_f / eta
        wall = ((1.0 - wall_lambda) / (1.0 - 0.33 * wall_lambda)) ** ((3.3 + 0.085 * re) / (1.0 + 0.1 * re))
        v = 0.5 * v + 0.5 * stokes / (1.0 + 0.15 * re ** 0.687) * wall
    return v


def observed_order(h, v):
    """p with v_i = v* + C h_i^p through three points (bisection on the ratio of differences)."""
    target = (v[0] - v[1]) / (v[1] - v[2])
    f = lambda p: (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - target  # noqa: E731
    lo, hi = 0.05, 6.0
    if f(lo) * f(hi) > 0:
        return math.nan
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: settling_study.py OUT")
    out = sys.argv[1]
    rows = []
    for path in sorted(glob.glob(os.path.join(out, "*", "summary.json"))):
        s = json.load(open(path))
        grain = s["grain_settling"][0]
        d = 2.0 * grain["radius_m"]
        drho = s["grain_density_kg_m3"] - s["fluid_density_kg_m3"]
        args = (d, drho, s["fluid_density_kg_m3"], s["viscosity_Pa_s"], s["gravity_m_s2"])
        rows.append({"coupling_model": s.get("coupling_model", "cell_centre"),
                     "viscosity_Pa_s": s["viscosity_Pa_s"], "d_over_dx": s["d_over_dx_min"], "tau": s["tau"],
                     "status": s["status"], "settling_m_s": grain["settling_velocity_m_s"],
                     "reynolds": grain["reynolds"], "unbounded_m_s": schiller_naumann(*args),
                     "walls_m_s": schiller_naumann(*args, wall_lambda=d / s["box_width_m"]),
                     "wall_time_s": s["wall_time_s"]})
    rows.sort(key=lambda r: (-r["viscosity_Pa_s"], r["d_over_dx"]))
    with open(os.path.join(out, "study.csv"), "w") as f:
        keys = list(rows[0].keys())
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(str(r[k]) for k in keys) + "\n")
    print("| eta [Pa s] | d/dx | tau | Re | settling [mm/s] | SN unbounded | SN + walls | Sabo / (SN + walls) |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['viscosity_Pa_s']} | {r['d_over_dx']:.0f} | {r['tau']:.3f} | {r['reynolds']:.2f} | "
              f"{1000 * r['settling_m_s']:.2f} | {1000 * r['unbounded_m_s']:.2f} | {1000 * r['walls_m_s']:.2f} | "
              f"{r['settling_m_s'] / r['walls_m_s']:.3f} |")
    print()
    for eta in sorted({r["viscosity_Pa_s"] for r in rows}, reverse=True):
        group = [r for r in rows if r["viscosity_Pa_s"] == eta]
        if len(group) != 3:
            continue
        h = [1.0 / r["d_over_dx"] for r in group]
        v = [r["settling_m_s"] for r in group]
        p = observed_order(h, v)
        first = v[2] + (v[2] - v[1]) * h[2] / (h[1] - h[2])  # extrapolated assuming first order (the two finest)
        print(f"eta {eta}: observed order {p:.2f}; extrapolated to dx -> 0 (first order from the two finest) "
              f"{1000 * first:.2f} mm/s = {first / group[0]['walls_m_s']:.3f} x SN + walls")


if __name__ == "__main__":
    main()
