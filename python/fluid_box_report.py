#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Report of a fluid-box run (grains in a closed box of fluid): settling.png (each grain's vertical velocity
against time, with Stokes' and Schiller & Naumann's settling velocities for an unbounded fluid; up to ten
grains), forces.png (grain 0's drag and buoyancy along Z), report.md. Usage: fluid_box_report.py OUT_DIR"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_common import read_csv, run_folder_summary, write_markdown  # noqa: E402


def main():
    out, s = run_folder_summary("fluid_box_report.py")
    g = read_csv(os.path.join(out, "grains_series.csv"))
    settling = s.get("grain_settling", [])
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for k in range(min(10, s["grains"])):
        rows = g["grain"] == k
        ax.plot(g["time_s"][rows], -1000.0 * g["vz_m_s"][rows], label=f"grain {k}" if k < 5 else None)
    if settling:
        first = settling[0]
        ax.axhline(1000.0 * first["stokes_velocity_m_s"], color="k", ls=":", label="Stokes, unbounded (grain 0)")
        ax.axhline(1000.0 * first["schiller_naumann_velocity_m_s"], color="k", ls="--",
                   label="Schiller & Naumann, unbounded (grain 0)")
    ax.axvline(s["averaged_from_s"], color="0.6", lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("settling velocity −v_z [mm/s]")
    ax.set_title(f"{s['case']}: d/dx ≥ {s['d_over_dx_min']:.1f}; mean taken right of the grey line")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "settling.png"), dpi=130)
    plt.close(fig)
    rows = g["grain"] == 0
    fig, ax = plt.subplots(figsize=(6.5, 3.4))
    ax.plot(g["time_s"][rows], 1000.0 * g["drag_z_N"][rows], label="drag")
    ax.plot(g["time_s"][rows], 1000.0 * g["buoyancy_z_N"][rows], label="buoyancy")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("force along Z on grain 0 [mN]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "forces.png"), dpi=120)
    plt.close(fig)
    lines = [f"# Fluid box {s['case']}", "", "| quantity | value |", "|---|---|",
             f"| status | {s['status']} ({s['ended_by']}) |",
             f"| box | {s['box_length_m']:.4g} x {s['box_width_m']:.4g} x {s['box_height_m']:.4g} m, "
             f"{s['grains']} grains of {s['grain_density_kg_m3']:.0f} kg/m³ in {s['fluid_density_kg_m3']:.0f} kg/m³, "
             f"η = {s['viscosity_Pa_s']:.4g} Pa·s |",
             f"| lattice | dx = {s['dx_m']:.4g} m, dt = {s['dt_s']:.4g} s, tau = {s['tau']:.4f}, d/dx ≥ "
             f"{s['d_over_dx_min']:.1f}, {s['substeps']} DEM sub-steps |",
             f"| buoyancy | {'on, volume: ' + s['buoyancy_volume'] if s['buoyancy'] else 'off'} |",
             f"| max relative mass drift | {s['max_relative_mass_drift']:.2e} |",
             f"| wall time | {s['wall_time_s']:.1f} s ({s['threads']} threads) |", "",
             f"Settling velocities, mean over t ≥ {s['averaged_from_s']:.4g} s ({s['averaged_samples']} samples); "
             "the predictions are for an unbounded fluid (walls slow a grain: docs/results/settling.md).", "",
             "| grain | radius [mm] | settling [mm/s] | Re | Stokes [mm/s] | Schiller–Naumann [mm/s] |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {p['grain']} | {1000 * p['radius_m']:.3g} | {1000 * p['settling_velocity_m_s']:.4g} | "
              f"{p['reynolds']:.3g} | {1000 * p['stokes_velocity_m_s']:.4g} | "
              f"{1000 * p['schiller_naumann_velocity_m_s']:.4g} |" for p in settling]
    write_markdown(out, "report.md", lines, [("Settling velocity", "settling.png"), ("Forces on grain 0", "forces.png")])


if __name__ == "__main__":
    main()
