#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Report of a fluid-box run (grains in a box of fluid): settling.png (each grain's vertical velocity against
time, with Stokes' and Schiller & Naumann's settling velocities for an unbounded fluid; up to ten grains),
forces.png (grain 0's drag and buoyancy along Z), report.md. Grains held in a driven flow (grains.held):
flow.png (the fluid's mean velocity along X and the force along X on grain 0) instead, and the periodic
array's drag against Hasimoto's where the summary has it. Usage: fluid_box_report.py OUT_DIR"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_common import read_csv, run_folder_summary, write_markdown  # noqa: E402


def header(s):
    """The run's table: status, box, lattice, coupling, mass drift, wall time."""
    return [f"# Fluid box {s['case']}", "", "| quantity | value |", "|---|---|",
            f"| status | {s['status']} ({s['ended_by']}) |",
            f"| box | {s['box_length_m']:.4g} x {s['box_width_m']:.4g} x {s['box_height_m']:.4g} m, "
            f"{s['grains']} grains of {s['grain_density_kg_m3']:.0f} kg/m³ in {s['fluid_density_kg_m3']:.0f} kg/m³, "
            f"η = {s['viscosity_Pa_s']:.4g} Pa·s |",
            f"| lattice | dx = {s['dx_m']:.4g} m, dt = {s['dt_s']:.4g} s, tau = {s['tau']:.4f}, d/dx ≥ "
            f"{s['d_over_dx_min']:.1f}, {s['substeps']} DEM sub-steps |",
            f"| coupling | {s.get('coupling_model', 'cell_centre')}; buoyancy "
            f"{'on, volume: ' + s['buoyancy_volume'] if s['buoyancy'] else 'off'} |",
            f"| max relative mass drift | {s['max_relative_mass_drift']:.2e} |",
            f"| wall time | {s['wall_time_s']:.1f} s ({s['threads']} threads) |", ""]


def held_report(out, s, g, head):
    """A driven flow past held grains: the flow's approach to steady and the drag along X."""
    series = read_csv(os.path.join(out, "series.csv"))
    rows = g["grain"] == 0
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 5.4), sharex=True)
    top.plot(series["time_s"], 1000.0 * series["fluid_mean_vx_m_s"])
    top.set_ylabel("fluid's mean u_x [mm/s]")
    top.set_title(f"{s['case']}: drive {s['drive_x_m_s2']:.4g} m/s² along X\n(means taken right of the grey line)",
                  fontsize=10)
    bottom.plot(g["time_s"][rows], 1000.0 * (g["drag_x_N"][rows] + g["buoyancy_x_N"][rows]), label="drag + buoyancy")
    bottom.set_ylabel("F_x on grain 0 [mN]")
    bottom.set_xlabel("time [s]")
    for ax in (top, bottom):
        ax.axvline(s["averaged_from_s"], color="0.6", lw=0.8)
        ax.grid(alpha=0.3)
    bottom.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "flow.png"), dpi=130)
    plt.close(fig)
    lines = head + [f"Held grains (periodic along {s['periodic']}), means over t ≥ {s['averaged_from_s']:.4g} s "
                    f"({s['averaged_samples']} samples): the fluid's mean velocity along X "
                    f"{1000 * s['fluid_mean_velocity_x_m_s']:.5g} mm/s.", "",
                    "| grain | radius [mm] | force x [mN] | force y [mN] | force z [mN] |", "|---|---|---|---|---|"]
    lines += [f"| {p['grain']} | {1000 * p['radius_m']:.3g} | {1000 * p['force_x_N']:.5g} | "
              f"{1000 * p['force_y_N']:.3g} | {1000 * p['force_z_N']:.3g} |" for p in s.get("grain_settling", [])]
    a = s.get("periodic_array")
    if a:
        lines += ["", "A simple cubic array (one sphere in a box periodic every way): its drag, the body force on the "
                  "whole box (the pressure-driven flow's), against Stokes' drag at the mean velocity times the "
                  "array's correction (Hasimoto 1959; Sangani & Acrivos 1982).", "",
                  "| solid fraction | drag [mN] | Stokes [mN] | correction K | drag / (Stokes × K) | Re |",
                  "|---|---|---|---|---|---|",
                  f"| {a['solid_fraction']:.4f} | {1000 * a['drag_N']:.5g} | {1000 * a['stokes_drag_N']:.5g} | "
                  f"{a['array_correction']:.4f} | {a['drag_over_prediction']:.4f} | {a['reynolds']:.3g} |"]
    write_markdown(out, "report.md", lines, [("The flow and the drag", "flow.png")])


def main():
    out, s = run_folder_summary("fluid_box_report.py")
    g = read_csv(os.path.join(out, "grains_series.csv"))
    if s.get("grains_held"):
        held_report(out, s, g, header(s))
        return
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
    lines = header(s) + [
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
