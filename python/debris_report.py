#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Report of a debris run in the channel (reference case C5): the barrier's normal force normalised by W sin θ
(forces.png: total, solid and fluid with their peaks; the fluid alone: fluid_force.png), the non-retained
fractions (non_retained.png), a fed run's inflow (inflow.png), report.md. A run with grains whose summary names a dry twin (the same
grains without fluid, output.dry_twin_dir) draws the twin's curves beside its own.
Usage: debris_report.py OUT_DIR"""
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from design_report import design_section  # noqa: E402
from report_common import read_csv, run_folder_summary, write_markdown  # noqa: E402


def save_time_plot(fig, ax, out, name, ylabel, title=None):
    """A figure over time: its axes' labels, its legend, written as OUT/name."""
    ax.set_xlabel("time [s]")
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=120)
    plt.close(fig)


def newtons_axis(ax, weight):
    """The force in kN on the right, beside the ratio to the weight component W sin θ on the left."""
    if weight:
        right = ax.secondary_yaxis("right", functions=(lambda r: r * weight / 1e3, lambda f: f * 1e3 / weight))
        right.set_ylabel("F [kN]")


def fluid_only(out, s, series):
    fig, ax = plt.subplots(figsize=(7, 3.6))
    scale = s.get("W_sin_theta_N")  # null on a level channel: newtons then
    unit = scale if scale else 1.0
    ax.plot(series["time_s"], series["fluid_force_normal_N"] / unit, label="fluid, normal to the face")
    ax.plot(series["time_s"], series["fluid_force_peak_N"] / unit, lw=0.6, alpha=0.6,
            label="|F| peak within each interval")
    tp = s.get("time_of_fluid_force_normal_max_s")
    if tp is not None and not math.isnan(tp):
        ax.plot([tp], [s["fluid_force_normal_max_N"] / unit], "v", color="tab:blue", ms=6,
                label="exact peak (every step)")
    if scale:
        newtons_axis(ax, scale)
    save_time_plot(fig, ax, out, "fluid_force.png", "F / (W sin θ)" if scale else "F [N]")
    fig, ax = plt.subplots(figsize=(7, 3.0))
    ax.plot(series["time_s"], series["fluid_non_retained_fraction"], label="non-retained")
    if "fluid_over_crest_fraction" in series:
        ax.plot(series["time_s"], series["fluid_over_crest_fraction"], ls="-.", label="went over the crest")
    if "fluid_left_domain_fraction" in series:
        ax.plot(series["time_s"], series["fluid_left_domain_fraction"], ls="--", label="left the domain")
    save_time_plot(fig, ax, out, "non_retained.png", "share of the fluid")
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
             *fluid_split_rows(s),
             f"| max relative mass drift | {s['max_relative_mass_drift']:.2e} |",
             f"| wall time | {s['wall_time_s']:.1f} s ({s['threads']} threads) |"] + domain_rows(s)
    rows, images = inflow_section(out, s)
    write_report(out, lines + rows,
                 [("Fluid force on the barrier", "fluid_force.png"), ("Fluid non-retained fraction", "non_retained.png")]
                 + images)


def fluid_split_rows(s):
    """How the fluid got behind the barrier (docs/analysis.md, "Overflow"); nothing for a summary without it."""
    if s.get("fluid_spread_behind_fraction") is None:
        return []
    return [f"| fluid that entered behind the barrier | over the crest {s['fluid_over_crest_fraction']:.4f}, "
            f"through the outlets {s['fluid_through_outlets_fraction']:.4f}, moved there by the free surface's "
            f"conversions (not flow) {s['fluid_spread_behind_fraction']:.4f} |"]


def inflow_section(out, s):
    """A run fed from a hydrograph: the fluid's (and the grains') volume that entered against the hydrograph's
    integral (inflow.png), and the report's rows; nothing for a released block."""
    if s.get("inflow_volume_m3") is None:
        return [], []
    fig, ax = plt.subplots(figsize=(7, 3.2))
    fluid = read_csv(os.path.join(out, "inflow.csv"))
    ax.plot(fluid["time_s"], fluid["hydrograph_volume_m3"], color="tab:blue", label="fluid: hydrograph ∫ Q (1 − c) dt")
    ax.plot(fluid["time_s"], fluid["inflow_volume_m3"], "--", color="tab:blue", label="fluid: entered")
    rows = [f"| inflow, fluid | {s['inflow_volume_m3']:.4f} m³ entered of the hydrograph's "
            f"{s['inflow_hydrograph_volume_m3']:.4f} m³ (u = {s['inflow_velocity_m_s']:.3g} m/s) |"]
    if s.get("inflow_grains") is not None:
        grains = read_csv(os.path.join(out, "inflow_grains.csv"))
        ax.plot(grains["time_s"], grains["hydrograph_solid_volume_m3"], color="tab:brown",
                label="grains: hydrograph ∫ Q c dt")
        ax.plot(grains["time_s"], grains["inflow_solid_volume_m3"], "--", color="tab:brown", label="grains: entered")
        rows.append(f"| inflow, grains | {s['inflow_grains']} grains, {s['inflow_solid_volume_m3']:.4f} m³ entered of "
                    f"the hydrograph's {s['inflow_hydrograph_solid_volume_m3']:.4f} m³ (a batch every "
                    f"{s['inflow_batch_interval_s']:.3g} s) |")
    save_time_plot(fig, ax, out, "inflow.png", "volume [m³]", title="inflow through the section")
    return rows, [("Inflow: the hydrograph's volumes and what entered", "inflow.png")]


def domain_rows(s, weight="W sin θ"):
    """The channel's top and what left the domain (summaries of runs before the open channel lack them)."""
    if "channel_top" not in s:
        return []
    rows = [f"| channel | walls {s['wall_height_m']:.3g} m, barrier {s['barrier_height_m']:.3g} m, "
            + (f"open above to {s['domain_height_m']:.3g} m |" if s["channel_top"] == "open" else "a lid on the walls |")]
    if s.get("fluid_left_end_fraction") is not None:
        rows.append(f"| fluid that left the domain | outflow {100 * s['fluid_left_end_fraction']:.2f} %, over the side "
                    f"walls {100 * s['fluid_left_sides_fraction']:.2f} %, through the top "
                    f"{100 * s['fluid_left_top_fraction']:.2f} % of the starting mass |")
    if s.get("force_normal_max_mean_50ms_over_W_sin_theta") is not None:
        rows.append(f"| largest 50 ms mean of the normal force | "
                    f"{number(s['force_normal_max_mean_50ms_over_W_sin_theta'])} {weight} at "
                    f"{number(s['time_of_force_normal_max_mean_50ms_s'])} s"
                    + (" (the every-step peak includes the lattice's acoustic pulse at arrival) |" if "rheology" in s
                       else " |"))
    return rows


def write_report(out, lines, images):
    """report.md: the run's lines and charts, then the design comparison (docs/design.md)."""
    design_md, design_chart = design_section(out)
    write_markdown(out, "report.md", lines + design_md, images + ([design_chart] if design_chart else []))


def number(value, fmt=".3f"):
    return "–" if value is None or (isinstance(value, float) and math.isnan(value)) else format(value, fmt)


def with_grains(out, s, series):
    twin_dir = s.get("dry_twin_dir") or ""
    twin = twin_series = None
    if twin_dir and os.path.exists(os.path.join(twin_dir, "summary.json")):
        with open(os.path.join(twin_dir, "summary.json")) as f:
            twin = json.load(f)
        twin_series = read_csv(os.path.join(twin_dir, "series.csv"))
    t = series["time_s"]
    fig, ax = plt.subplots(figsize=(7.5, 4.0))
    ax.plot(t, series["force_normal_over_W_sin_theta"], color="k", label="total")
    ax.plot(t, series["solid_force_normal_over_W_sin_theta"], color="tab:brown", label="solid (contacts)")
    if s["mode"] == "coupled":
        ax.plot(t, series["fluid_force_normal_over_W_sin_theta"], color="tab:blue", label="fluid")
    # the exact peaks (tracked every step; a one-step spike falls between the rows)
    peaks = [("force_normal", "k"), ("solid_force_normal", "tab:brown")]
    if s["mode"] == "coupled":
        peaks.append(("fluid_force_normal", "tab:blue"))
    for key, colour in peaks:
        tp, value = s.get(f"time_of_{key}_max_s"), s.get(f"{key}_max_over_W_sin_theta")
        if tp is not None and value is not None and not math.isnan(tp):
            ax.plot([tp], [value], "v", color=colour, ms=6)
    ax.plot([], [], "v", color="k", label="exact peaks (every step)")
    newtons_axis(ax, s.get("W_tot_sin_theta_N"))
    if twin_series is not None:  # in newtons over this run's W_tot sin θ: the same scale for both
        ax.plot(twin_series["time_s"], twin_series["force_normal_N"] / s["W_tot_sin_theta_N"], color="tab:gray",
                ls="--", label="dry twin (the same grains), total")
    save_time_plot(fig, ax, out, "forces.png", "F_n / (W_tot sin θ)")
    fig, ax = plt.subplots(figsize=(7.5, 3.2))
    ax.plot(t, series["solid_non_retained_fraction"], color="tab:brown", label="solid")
    if s["mode"] == "coupled":
        ax.plot(t, series["fluid_non_retained_fraction"], color="tab:blue", label="fluid")
        if "fluid_left_domain_fraction" in series:
            ax.plot(t, series["fluid_left_domain_fraction"], color="tab:blue", ls=":", label="fluid, left the domain")
    if twin_series is not None:
        ax.plot(twin_series["time_s"], twin_series["solid_non_retained_fraction"], color="tab:gray", ls="--",
                label="dry twin, solid")
    save_time_plot(fig, ax, out, "non_retained.png", "non-retained fraction")
    title = "grains and fluid" if s["mode"] == "coupled" else "grains, dry"
    lines = [f"# Debris ({title}) {s['case']}", "", "| quantity | value |", "|---|---|",
             f"| status | {s['status']} ({s['ended_by']}) {s.get('failure', '')} |",
             (f"| grains | fed through the inflow: V_s = {s['solid_volume_m3']:.3f} m³ so far |"
              if s["grain_placement"] == "inflow" else
              f"| grains | {s['grains']} ({s['grain_placement']}), V_s = {s['solid_volume_m3']:.3f} m³, "
              f"V_s/V_box = {s['solid_fraction_actual']:.3f} (asked {s['solid_fraction']:.3f}) |"),
             f"| W_tot sin θ | {number(s['W_tot_sin_theta_N'], '.4g')} N |"]
    if s["mode"] == "coupled":
        lines += [f"| fluid | {s['rheology']}, {s['fluid_volume_m3']:.3f} m³; dx = {s['dx_m']:.4g} m, "
                  f"dt = {s['dt_s']:.4g} s, {s['substeps']} DEM sub-steps, buoyancy {'on' if s['buoyancy'] else 'off'} |"]
    for label, key in (("total", "force_normal"), ("solid", "solid_force_normal"), ("fluid", "fluid_force_normal")):
        if label == "fluid" and s["mode"] != "coupled":
            continue
        lines.append(f"| peak normal force, {label} | {number(s[f'{key}_max_over_W_sin_theta'])} W_tot sin θ "
                     f"({number(s[f'{key}_max_N'], '.4g')} N) at t = {number(s[f'time_of_{key}_max_s'])} s |")
    lines.append(f"| solid non-retained at the end | {number(s['solid_non_retained_fraction'], '.4f')} |")
    if s["mode"] == "coupled":
        lines += [f"| fluid non-retained at the end | {number(s['fluid_non_retained_fraction'], '.4f')} |",
                  *fluid_split_rows(s),
                  f"| max relative mass drift | {s['max_relative_mass_drift']:.2e} |"]
    if twin is not None:
        lines += [f"| dry twin ({twin_dir}) | peak total {number(twin['force_normal_max_N'] / s['W_tot_sin_theta_N'])} "
                  f"W_tot sin θ of this run ({number(twin['force_normal_max_N'], '.4g')} N) at "
                  f"t = {number(twin['time_of_force_normal_max_s'])} s; solid non-retained "
                  f"{number(twin['solid_non_retained_fraction'], '.4f')} |"]
    lines += domain_rows(s, "W_tot sin θ" if s["mode"] == "coupled" else "W_s sin θ")
    lines.append(f"| max overlap | {100 * s['max_overlap_over_d']:.2f} % of d |")
    lines.append(f"| wall time | {s['wall_time_s']:.1f} s ({s['threads']} threads) |")
    rows, images = inflow_section(out, s)
    write_report(out, lines + rows,
                 [("Normal force on the barrier", "forces.png"), ("Non-retained fractions", "non_retained.png")]
                 + images)


def main():
    out, s = run_folder_summary("debris_report.py")
    series = read_csv(os.path.join(out, "series.csv"))
    if s.get("mode") in ("coupled", "dry"):
        with_grains(out, s, series)
    else:
        fluid_only(out, s, series)


if __name__ == "__main__":
    main()
