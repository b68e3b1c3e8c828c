#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Report of a dam-break run (issue 5): front.png (front Z = x/a against T = t sqrt(2g/a), with Martin &
Moyce's 1952 measurements), mass.png (relative mass drift), report.md. Usage: dam_break_report.py OUT_DIR"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_common import read_csv, run_folder_summary, write_markdown  # noqa: E402


def main():
    out, s = run_folder_summary("dam_break_report.py")
    series = read_csv(os.path.join(out, "series.csv"))
    points = s.get("front_vs_martin_moyce", [])
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ax.plot(series["T_scaled"], series["front_over_a"], "-", label="Sabo (floor cell ≥ 0.1 full)")
    ax.plot([p["T"] for p in points], [p["front_over_a_experiment"] for p in points], "ko", ms=4,
            label="Martin & Moyce (1952), n² = 2")
    ax.set_xlabel("T = t sqrt(2g/a)")
    ax.set_ylabel("Z = front / a")
    ax.set_title(f"{s['case']}: a = {s['column_width_m'] * 1000:.1f} mm = {s['column_width_m'] / s['dx_m']:.0f} cells")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "front.png"), dpi=130)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(6.5, 3.0))
    ax.plot(series["time_s"], series["mass_relative_drift"])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("relative mass drift")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mass.png"), dpi=120)
    plt.close(fig)
    lines = [f"# Dam break {s['case']}", "", "| quantity | value |", "|---|---|",
             f"| status | {s['status']} ({s['ended_by']}) |",
             f"| column a x h | {s['column_width_m']:.4g} m x {s['column_height_m']:.4g} m |",
             f"| lattice | dx = {s['dx_m']:.4g} m, dt = {s['dt_s']:.4g} s, {s['lattice_cells']} cells, {s['storage']} |",
             f"| tau, Mach | {s['tau']:.4f}, {s['mach']:.3f} |",
             f"| front at the end | {s['front_final_over_a']:.3f} a |",
             f"| RMS deviation from Martin & Moyce | {100 * s['front_rms_relative_error_vs_martin_moyce']:.1f} % "
             f"over {len(points)} points |",
             f"| max relative mass drift | {s['max_relative_mass_drift']:.2e} |",
             f"| wall time | {s['wall_time_s']:.1f} s ({s['threads']} threads, "
             f"{s['cell_updates_per_s'] / 1e6:.2f} million cell updates/s) |", "",
             "| T | Z experiment | Z Sabo |", "|---|---|---|"]
    lines += [f"| {p['T']:.2f} | {p['front_over_a_experiment']:.2f} | {p['front_over_a_sabo']:.2f} |" for p in points]
    write_markdown(out, "report.md", lines, [("Front position", "front.png"), ("Mass conservation", "mass.png")])


if __name__ == "__main__":
    main()
