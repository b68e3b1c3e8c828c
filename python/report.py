#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plots and report.md for one finished Sabo run.

    python3 python/report.py OUT_DIR

Reads summary.json, series.csv, barrier_piles.csv, barrier_maps.csv arching.csv and design_comparison.csv (docs/outputs.md)
and writes into OUT_DIR: force_history.png, non_retained.png, kinetic_energy.png, pile_forces.png,
force_maps.png, pressure_profile.png, arching.png, design_comparison.png, inflow.png (a run with an inflow) and report.md. Needs Debian's python3-numpy and python3-matplotlib.
"""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from design_report import design_section  # noqa: E402
from report_common import read_csv, run_folder_summary, write_markdown  # noqa: E402


def fmt(v, unit="", digits=4):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "–"
    if isinstance(v, (int, float)):
        return f"{v:.{digits}g}{(' ' + unit) if unit else ''}"
    return str(v)


def mark_times(ax, s):
    # labels at staggered heights: t1 and t2 are often close together
    for k, (key, label, style) in enumerate((("first_impact_time_s", "t1", ":"), ("time_of_max_local_force_s", "t2", "--"),
                                             ("time_of_max_global_force_s", "t3", "-."))):
        t = s.get(key)
        if t is not None:
            ax.axvline(t, color="k", linestyle=style, linewidth=0.8)
            ax.text(t, 0.97 - 0.07 * k, f" {label}", va="top", fontsize=8, transform=ax.get_xaxis_transform())


def mark_peak(ax, t, value, color, label):
    """The exact peak (tracked every step) on a curve of samples, which may miss it between two rows."""
    if t is not None and value is not None and math.isfinite(value):
        ax.plot([t], [value], "v", color=color, ms=6, label=label)


def plot_forces(out, s, series):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    t = series["time_s"]
    ax.plot(t, series["barrier_force_resultant_peak_N"] / 1e3, color="0.7", label="resultant, peak per interval")
    ax.plot(t, series["barrier_force_resultant_N"] / 1e3, color="tab:blue", label="resultant |F_G|")
    ax.plot(t, series["barrier_force_normal_N"] / 1e3, color="tab:orange", label="normal F_n")
    ax.plot(t, series["barrier_force_tangential_N"] / 1e3, color="tab:green", label="tangential")
    mark_peak(ax, s.get("time_of_max_global_force_s"), (s.get("max_global_force_N") or math.nan) / 1e3, "tab:blue",
              f"peak |F_G| {fmt((s.get('max_global_force_N') or math.nan) / 1e3, 'kN')}")
    mark_peak(ax, s.get("time_of_max_normal_force_s"), (s.get("max_normal_force_N") or math.nan) / 1e3, "tab:orange",
              f"peak F_n {fmt((s.get('max_normal_force_N') or math.nan) / 1e3, 'kN')}")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("barrier force [kN]")
    ax.set_title(f"{s['case']}: global barrier force")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    mark_times(ax, s)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "force_history.png"), dpi=110)
    plt.close(fig)


def positive(values):
    """Zeros (no grain downstream yet, all at rest) left out of a log axis rather than drawn at a floor."""
    v = np.asarray(values, dtype=float)
    return np.where(v > 0, v, np.nan)


def plot_series(out, s, series):
    t = series["time_s"]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(t, series["non_retained_fraction"], label="passed the barrier")
    if "over_crest_fraction" in series and float(np.nanmax(series["over_crest_fraction"])) > 0.0:
        ax.plot(t, series["over_crest_fraction"], "--", label="of which over its crest")
    ax.legend(fontsize=8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("share of the grains' mass [-]")
    ax.set_ylim(0, max(0.05, 1.1 * float(np.nanmax(series["non_retained_fraction"]))))
    ax.set_title(f"non-retained fraction (final {fmt(s.get('non_retained_fraction'))})")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "non_retained.png"), dpi=110)
    plt.close(fig)

    # the total and the per-grain mean downstream differ by the grain count: one panel each
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    top.semilogy(t, positive(series["kinetic_energy_translational_J"] + series["kinetic_energy_rotational_J"]),
                 label="all grains, total (translation + rotation)")
    top.set_ylabel("kinetic energy [J]")
    top.set_title("kinetic energy of the grains")
    bottom.semilogy(t, positive(series["downstream_mean_kinetic_energy_J"]), color="tab:orange",
                    label="downstream of the barrier, mean per grain")
    bottom.set_ylabel("kinetic energy per grain [J]")
    bottom.set_xlabel("time [s]")
    for ax in (top, bottom):
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "kinetic_energy.png"), dpi=110)
    plt.close(fig)


def plot_piles(out, s, piles):
    t = piles["time_s"]
    fig, ax = plt.subplots(figsize=(7, 4))
    summaries = s.get("piles") or []
    k = 0
    while f"pile_{k}_normal_force_N" in piles:
        line, = ax.plot(t, piles[f"pile_{k}_normal_force_N"] / 1e3, label=f"pile {k}")
        if k < len(summaries):
            p = summaries[k]
            mark_peak(ax, p.get("time_of_max_normal_force_s"), (p.get("max_normal_force_N") or math.nan) / 1e3,
                      line.get_color(), None)
        k += 1
    ax.plot([], [], "v", color="k", label="exact peak (every step)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("normal force [kN]")
    ax.set_title("normal force per pile (lines: series rows; ▼ the peaks of summary.json)")
    ax.grid(alpha=0.3)
    if k <= 10:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "pile_forces.png"), dpi=110)
    plt.close(fig)


def pressure_profile(s, maps, key):
    """Normal pressure over the barrier's height from one force map: the elements' normal forces summed in
    height bands of one element spacing, over the band's area (band height × channel width); and where the
    resultant acts (the normal-force-weighted mean height)."""
    n = s.get("barrier_face_normal") or [1.0, 0.0, 0.0]
    fn = maps[f"{key}_fx_N"] * n[0] + maps[f"{key}_fy_N"] * n[1] + maps[f"{key}_fz_N"] * n[2]
    z = maps["height_m"]
    levels = np.unique(np.round(z, 6))
    dz = float(np.min(np.diff(levels))) if len(levels) > 1 else 1.0
    edges = np.arange(float(np.min(z)) - dz / 2, float(np.max(z)) + dz, dz)
    force, _ = np.histogram(z, bins=edges, weights=fn)
    width = s.get("barrier_width_m") or s.get("channel_width_m") or 1.0
    centres = 0.5 * (edges[1:] + edges[:-1])
    total = float(np.sum(fn))
    at = float(np.sum(fn * z) / total) if abs(total) > 0 else math.nan
    return centres, force / (dz * width) / 1e3, at, total


def plot_pressure(out, s, maps, times):
    """What a designer draws: the pressure over the barrier's height at the peak and at the end."""
    end = "end (static: at rest)" if s.get("deposit_at_rest") else "end (not at rest)"
    fig, ax = plt.subplots(figsize=(5.5, 5))
    for key, label, color in (("t3", "max global force t3", "tab:red"), ("end", end, "tab:blue")):
        if f"{key}_fx_N" not in maps:
            continue
        z, p, at, total = pressure_profile(s, maps, key)
        ax.step(p, z, where="mid", color=color,
                label=f"{label}, t = {fmt(times.get(key), 's')}: F_n {fmt(total / 1e3, 'kN')}")
        if math.isfinite(at):
            ax.axhline(at, color=color, ls=":", lw=1, label=f"resultant acts at {fmt(at, 'm', 3)}")
    ax.axvline(0, color="k", lw=0.6)
    ax.set_xlabel("normal pressure on the barrier [kPa] (over the channel width)")
    ax.set_ylabel("height above the bed [m]")
    ax.set_title("pressure over the barrier's height")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "pressure_profile.png"), dpi=110)
    plt.close(fig)


def plot_maps(out, s, maps, times):
    end = "end (static: at rest)" if s.get("deposit_at_rest") else "end (not at rest)"
    panels = [("t1", "first impact t1"), ("t2", "max local force t2"), ("t3", "max global force t3"),
              ("end", end), ("envelope", "envelope of the max")]
    fig, axes = plt.subplots(1, len(panels), figsize=(3.6 * len(panels), 3.8), sharey=True)
    for ax, (key, title) in zip(axes, panels):
        values = (maps["envelope_N"] if key == "envelope" else maps[f"{key}_magnitude_N"]) / 1e3
        vmax = max(1e-9, float(np.nanmax(values)))  # each map on its own scale: the end map is much smaller
        sc = ax.scatter(maps["y_m"], maps["height_m"], c=values, s=12, marker="s", cmap="viridis", vmin=0, vmax=vmax)
        when = "" if key == "envelope" else f"\nt = {fmt(times.get(key), 's')}"
        ax.set_title(title + when, fontsize=9)
        ax.set_xlabel("Y [m]")
        ax.set_aspect("equal")
        fig.colorbar(sc, ax=ax, shrink=0.7, label="element force [kN]")
    axes[0].set_ylabel("height along the face [m]")
    fig.savefig(os.path.join(out, "force_maps.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)


def plot_arching(out, s, arching):
    fig, ax = plt.subplots(figsize=(6, 4))
    h_bar = s.get("barrier_height_m", 1.0)
    outlets = sorted(set(int(o) for o in arching["outlet"]))
    for o in outlets:
        sel = (arching["outlet"] == o) & (arching["halted"] == 1)
        ax.plot(arching["t_stop_minus_t0_s"][sel], arching["z_hi_m"][sel] / h_bar, "o", label=f"outlet {o}")
    ax.set_xlabel("t_stop − t0 [s]")
    ax.set_ylabel("top of halted interval / H_bar [-]")
    ax.set_ylim(0, 1.05)
    ax.set_title(f"arching: H_arch/H_bar = {fmt(s.get('arch_height_ratio'))}, {s.get('clogging_mechanism', '')}")
    ax.grid(alpha=0.3)
    if 0 < len(outlets) <= 10:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "arching.png"), dpi=110)
    plt.close(fig)


def plot_inflow(out, inflow):
    """The grains' volume the hydrograph carried and the volume that entered, both cumulative."""
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(inflow["time_s"], inflow["hydrograph_solid_volume_m3"], label="hydrograph: ∫ Q c dt")
    ax.plot(inflow["time_s"], inflow["inflow_solid_volume_m3"], "--", label="entered (grains placed)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("grains' volume [m³]")
    ax.set_title("inflow through the section")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "inflow.png"), dpi=110)
    plt.close(fig)


def map_times(path):
    times = {}
    with open(path) as f:
        for ln in f:
            if ln.startswith("# map times"):
                parts = ln.split(":", 1)[1].split()
                for k in range(0, len(parts) - 1, 2):
                    times[parts[k]] = float(parts[k + 1])
    return times


def end_load_rows(s):
    """The load at the end: the static load of a deposit at rest, else what it is (the grains still moved)."""
    if s.get("deposit_at_rest"):
        return [("static global force (the deposit at rest)", fmt(s.get("static_global_force_N"), "N")),
                ("F_max / F_static", fmt(s.get("max_over_static_global_force"))),
                ("static X force / deposit weight (1 − non-retained) M g sin θ",
                 f"{fmt(s.get('static_force_x_over_deposit_weight'))} (bed {fmt(s.get('end_bed_force_x_N'), 'N')}, "
                 f"side walls {fmt(s.get('end_side_walls_force_x_N'), 'N')})")]
    why = "interrupted" if s.get("status") == "interrupted" else f"ended by {s.get('ended_by')}"
    return [(f"global force at the end ({why}, the grains still moving: not a static load)",
             fmt(s.get("end_global_force_N"), "N")),
            ("F_max / F_end (not at rest)", fmt(s.get("max_over_end_global_force"))),
            ("X force at the end / deposit weight (1 − non-retained) M g sin θ (not at rest)",
             f"{fmt(s.get('end_force_x_over_deposit_weight'))} (bed {fmt(s.get('end_bed_force_x_N'), 'N')}, "
             f"side walls {fmt(s.get('end_side_walls_force_x_N'), 'N')})")]


def main():
    out, s = run_folder_summary("report.py")
    at_rest = bool(s.get("deposit_at_rest"))
    series = read_csv(os.path.join(out, "series.csv"))
    has_barrier = s.get("barrier_type", "none") != "none"
    images = []
    if has_barrier:
        plot_forces(out, s, series)
        images.append(("Global barrier force (t1 first impact, t2 max local force, t3 max global force)",
                       "force_history.png"))
    plot_series(out, s, series)
    images += [("Non-retained fraction", "non_retained.png"), ("Kinetic energy", "kinetic_energy.png")]
    if has_barrier:
        plot_piles(out, s, read_csv(os.path.join(out, "barrier_piles.csv")))
        images.append(("Normal force per pile", "pile_forces.png"))
        maps_path = os.path.join(out, "barrier_maps.csv")
        maps = read_csv(maps_path)
        plot_maps(out, s, maps, map_times(maps_path))
        images.append(("Local force maps (one point per barrier element)", "force_maps.png"))
        plot_pressure(out, s, maps, map_times(maps_path))
        images.append(("Pressure over the barrier's height at the peak and at the end", "pressure_profile.png"))
        if s.get("outlets"):
            plot_arching(out, s, read_csv(os.path.join(out, "arching.csv")))
            images.append(("Arching: halted intervals", "arching.png"))

    fed = s.get("inflow_grains") is not None
    if fed:
        plot_inflow(out, read_csv(os.path.join(out, "inflow.csv")))
        images.append(("Inflow: the hydrograph's grain volume and what entered", "inflow.png"))
    grains = f"{s.get('particles')} released, {s.get('inflow_grains')} fed" if fed else s.get("particles")
    rows = [("status", s.get("status")), ("ended by", s.get("ended_by")),
            ("simulated time", fmt(s.get("simulated_time_s"), "s")), ("grains", grains),
            ("solid volume", fmt(s.get("solid_volume_m3"), "m³")), ("slope", fmt(s.get("slope_deg"), "°")),
            ("barrier", f"{s.get('barrier_type')} {s.get('barrier_orientation')} {s.get('barrier_configuration')} "
                        f"({s.get('barrier_model')})"),
            ("outlet width S/r", fmt(s.get("outlet_width_over_r"))),
            ("non-retained fraction", fmt(s.get("non_retained_fraction"))),
            ("of the grains' mass: over the crest, through the outlets",
             f"{fmt(s.get('solid_over_crest_fraction'))}, {fmt(s.get('solid_through_outlets_fraction'))}"),
            ("channel: top, end", f"{s.get('channel_top')}, {s.get('channel_end')} (left at the end "
                                  f"{fmt(s.get('solid_left_end_fraction'))}, over the side walls "
                                  f"{fmt(s.get('solid_spilled_fraction'))})"),
            ("first impact t1", fmt(s.get("first_impact_time_s"), "s")),
            ("max global force", f"{fmt(s.get('max_global_force_N'), 'N')} at {fmt(s.get('time_of_max_global_force_s'), 's')}"),
            ("max normal force", f"{fmt(s.get('max_normal_force_N'), 'N')} at {fmt(s.get('time_of_max_normal_force_s'), 's')}"),
            ("max local force", f"{fmt(s.get('max_local_force_N'), 'N')} at {fmt(s.get('time_of_max_local_force_s'), 's')}"),
            *end_load_rows(s),
            ("k_st, k_dyn (the reference study's coefficients: F_n,max/W over ρ_d g h² and over ρ_d v² h, "
             "ρ_d the grain density, h and v in the first metre upstream at the peak)",
             f"{fmt(s.get('k_st'))}, {fmt(s.get('k_dyn'))} (h = {fmt(s.get('upstream_flow_height_at_peak_m'), 'm')}, "
             f"v = {fmt(s.get('upstream_flow_velocity_at_peak_m_s'), 'm/s')})"),
            ("H_arch / H_bar (top of the highest halted grain interval in an outlet over the barrier's height)",
             fmt(s.get("arch_height_ratio"))),
            ("t_stop − t0 (when that interval halted, after the first impact t0)", fmt(s.get("t_stop_minus_t0_s"), "s")),
            ("clogging mechanism" + ("" if at_rest else " (provisional: the grains had not come to rest)"),
             s.get("clogging_mechanism")),
            ("wall time", fmt(s.get("wall_time_s"), "s")),
            ("threads", s.get("threads"))]
    md = [f"# Sabo run report: {s.get('case')}", "",
          f"Sabo {s.get('sabo_version')}. Definitions of every quantity: docs/outputs.md and docs/analysis.md.", "",
          "| quantity | value |", "|---|---|"]
    if fed:
        rows.append(("inflow: grains' volume entered / the hydrograph's",
                     f"{fmt(s.get('inflow_solid_volume_m3'), 'm³')} / {fmt(s.get('inflow_hydrograph_solid_volume_m3'), 'm³')} "
                     f"(u = {fmt(s.get('inflow_velocity_m_s'), 'm/s')}, a batch every {fmt(s.get('inflow_batch_interval_s'), 's')})"))
    md += [f"| {k} | {v} |" for k, v in rows]
    if s.get("piles"):
        end_label = "static normal force (at rest) [N]" if at_rest else "normal force at the end, not at rest [N]"
        md += ["", "## Piles", "", f"| pile | Y range [m] | max normal force [N] | at [s] | max basal moment [N·m] | {end_label} |",
               "|---|---|---|---|---|---|"]
        for p in s["piles"]:
            md.append(f"| {p['pile']} | {fmt(p['y_lo_m'])}–{fmt(p['y_hi_m'])} | {fmt(p['max_normal_force_N'])} | "
                      f"{fmt(p['time_of_max_normal_force_s'])} | {fmt(p['max_basal_moment_N_m'])} | "
                      f"{fmt(p.get('end_normal_force_N'))} |")
    if s.get("outlets"):
        md += ["", "## Outlets", "", "| outlet | Y range [m] | H_arch/H_bar | t_stop − t0 [s] | halted intervals | mechanism |",
               "|---|---|---|---|---|---|"]
        for k, o in enumerate(s["outlets"]):
            md.append(f"| {k} | {fmt(o['y_lo_m'])}–{fmt(o['y_hi_m'])} | {fmt(o['arch_height_ratio'])} | "
                      f"{fmt(o['t_stop_minus_t0_s'])} | {o['halted_intervals']} | {o['clogging_mechanism']} |")
    design_md, design_chart = design_section(out)
    md += design_md
    if design_chart:
        images.append(design_chart)
    write_markdown(out, "report.md", md, images)


if __name__ == "__main__":
    main()
