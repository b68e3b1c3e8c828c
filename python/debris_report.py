#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Report of a debris run in the channel (CASES C5, fluid alone for now): fluid_force.png (the fluid's
normal force on the barrier, normalised by W sin θ, with the interval peaks), non_retained.png (fluid
non-retained fraction), report.md. Usage: debris_report.py OUT_DIR"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_common import read_csv, run_folder_summary, write_markdown  # noqa: E402


def main():
    out, s = run_folder_summary("debris_report.py")
    series = read_csv(os.path.join(out, "series.csv"))
    fig, ax = plt.subplots(figsize=(7, 3.6))
    scale = s.get("W_sin_theta_N")  # null on a level channel: newtons then
    unit = scale if scale else 1.0
    ax.plot(series["time_s"], series["fluid_force_normal_N"] / unit, label="fluid, normal to the face")
    ax.plot(series["time_s"], series["fluid_force_peak_N"] / unit, lw=0.6, alpha=0.6,
            label="|F| peak within each interval")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("F / (W sin θ)" if scale else "F [N]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fluid_force.png"), dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(7, 3.0))
    ax.plot(series["time_s"], series["fluid_non_retained_fraction"])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("fluid non-retained fraction")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "non_retained.png"), dpi=120)
    plt.close(fig)
    lines = [f"# Debris (fluid only) {s['case']}", "", "| quantity | value |", "|---|---|",
             f"| status | {s['status']} ({s['ended_by']}) {s.get('failure', '')} |",
             f"| fluid | {s['rheology']}, {s['fluid_volume_m3']:.3f} m³, W sin θ = {s['W_sin_theta_N'] or 0:.4g} N |",
             f"| lattice | dx = {s['dx_m']:.4g} m, dt = {s['dt_s']:.4g} s, {s['lattice_cells']} cells, tau {s['tau']:.4f}, "
             f"Mach {s['mach']:.3f} |",
             f"| peak normal fluid force | {s['fluid_force_normal_max_N']:.4g} N"
             + (f" = {s['fluid_force_normal_max_over_W_sin_theta']:.3f} W sin θ" if scale else "")
             + f" at t = {s['time_of_fluid_force_normal_max_s']:.3f} s |",
             f"| normal fluid force at the end | {s['fluid_force_normal_end_N']:.4g} N |",
             f"| fluid non-retained fraction at the end | {s['fluid_non_retained_fraction']:.4f} |",
             f"| max relative mass drift | {s['max_relative_mass_drift']:.2e} |",
             f"| wall time | {s['wall_time_s']:.1f} s ({s['threads']} threads) |"]
    write_markdown(out, "report.md", lines,
                   [("Fluid force on the barrier", "fluid_force.png"), ("Fluid non-retained fraction", "non_retained.png")])


if __name__ == "__main__":
    main()
