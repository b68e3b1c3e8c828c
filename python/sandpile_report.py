#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Report of a sandpile run (reference case C1): heap.png (the heap seen from the side, the points of each side
and the fitted lines), kinetic_energy.png, report.md. Usage: sandpile_report.py OUT_DIR"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_common import read_csv, run_folder_summary, write_markdown  # noqa: E402


def read_heap(path):
    sides = {"left": [], "right": []}
    with open(path) as f:
        next(f)
        for ln in f:
            side, x, z, fit = ln.strip().split(",")
            sides[side].append((float(x), float(z), float(fit)))
    return sides


def plot_heap(out, s):
    g = read_csv(os.path.join(out, "final_grains.csv"))
    fig, ax = plt.subplots(figsize=(9, 4.5))
    ax.scatter(g["x_m"], g["z_m"], s=6, c=g["y_m"], cmap="Greys", alpha=0.5, linewidths=0)
    heap_path = os.path.join(out, "heap.csv")
    if os.path.exists(heap_path):
        for name, color in (("left", "tab:red"), ("right", "tab:blue")):
            pts = read_heap(heap_path)[name]
            if not pts:
                continue
            xs = [p[0] for p in pts]
            ax.plot(xs, [p[1] for p in pts], "o", color=color, ms=4, label=f"{name}: highest top per part")
            side = s[name]
            ax.plot([side["x_from_m"], side["x_to_m"]],
                    [side["intercept_m"] + side["slope"] * side["x_from_m"],
                     side["intercept_m"] + side["slope"] * side["x_to_m"]], "-", color=color,
                    label=f"{name}: {side['angle_deg']:.1f}°, R² {side['r2']:.3f}")
    ax.set_aspect("equal")
    ax.set_xlabel("X [m]")
    ax.set_ylabel("Z [m]")
    title = f"{s['case']}: {s['particles']} grains, d = {s['diameter_m'] * 1000:g} mm"
    if s.get("angle_of_repose_deg") is not None:
        title += f" — angle of repose {s['angle_of_repose_deg']:.2f}°"
    ax.set_title(title)
    ax.legend(fontsize=8, loc="center")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "heap.png"), dpi=130)
    plt.close(fig)


def plot_energy(out, s):
    series = read_csv(os.path.join(out, "series.csv"))
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.semilogy(series["time_s"], series["kinetic_energy_J"].clip(min=1e-30))
    if s.get("outlets_opened_at_s") is not None:
        ax.axvline(s["outlets_opened_at_s"], color="k", ls="--", lw=0.8, label="outlets opened")
        ax.legend(fontsize=8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("kinetic energy [J]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "kinetic_energy.png"), dpi=120)
    plt.close(fig)


def main():
    out, s = run_folder_summary("sandpile_report.py")
    plot_heap(out, s)
    plot_energy(out, s)
    lines = [f"# Sandpile {s['case']}", "", "| quantity | value |", "|---|---|",
             f"| status | {s['status']} ({s['ended_by']}) |",
             f"| grains, d | {s['particles']}, {s['diameter_m']} m |",
             f"| μ_s,pp / μ_r,pp / μ_s,pw / μ_r,pw | {s['mu_s_pp']:.3g} / {s['mu_r_pp']:.3g} / {s['mu_s_pw']:.3g} / {s['mu_r_pw']:.3g} |"]
    if s.get("angle_of_repose_deg") is not None:
        lines += [f"| angle of repose | {s['angle_of_repose_deg']:.2f}° |",
                  f"| left side | {s['left']['angle_deg']:.2f}° (R² {s['left']['r2']:.3f}, {s['left']['points']} points) |",
                  f"| right side | {s['right']['angle_deg']:.2f}° (R² {s['right']['r2']:.3f}, {s['right']['points']} points) |",
                  f"| heap height | {s['heap_height_m']:.4g} m{' (flat top)' if s['flat_top'] else ''} |",
                  f"| grains on the plate | {s['grains_on_plate']} |"]
    for key, label in (("outlets_opened_at_s", "outlets opened at"), ("stopped_at_s", "complete stop at")):
        if s.get(key) is not None:
            lines.append(f"| {label} | {s[key]:.4g} s |")
    lines.append(f"| wall time | {s['wall_time_s']:.1f} s ({s['threads']} threads) |")
    write_markdown(out, "report.md", lines,
                   [("Heap (side view, grey = depth in Y)", "heap.png"), ("Kinetic energy", "kinetic_energy.png")])
    if s.get("angle_of_repose_deg") is None or math.isnan(s.get("angle_of_repose_deg", math.nan)):
        print("no heap angle in summary.json", file=sys.stderr)


if __name__ == "__main__":
    main()
