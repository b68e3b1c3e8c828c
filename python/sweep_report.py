#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Table and design charts of a finished (or partly finished) `sabo sweep`.

    python3 python/sweep_report.py SWEEP_OUT_DIR

Reads SWEEP_OUT_DIR/sweep_cases.csv (written by `sabo sweep`) and each case's summary.json and
series.csv; writes sweep.csv (one row per case), the charts that the grid allows (docs/sweeps.md)
and sweep_report.md. Needs Debian's python3-numpy and python3-matplotlib.
"""
import csv
import json
import math
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from report_common import read_csv, write_markdown  # noqa: E402

COLUMNS = ["case", "status", "barrier_type", "barrier_configuration", "slope_deg", "outlet_width_over_r",
           "pile_width_over_r", "phi_small", "equivalent_radius_m", "s_over_r_star", "non_retained_fraction", "max_global_force_N",
           "max_normal_force_N", "max_pile_normal_force_N", "deposit_at_rest", "static_global_force_N",
           "max_over_static_global_force", "end_global_force_N", "max_over_end_global_force",
           "max_over_closed_global_force", "arch_height_ratio", "t_stop_minus_t0_s", "clogging_mechanism", "k_st",
           "k_dyn", "mean_downstream_kinetic_energy_J", "kinetic_energy_over_no_barrier"]
# The approaching flow at the gauge section and the coefficients back-calculated from it (docs/design.md).
DESIGN_COLUMNS = ["approach_flow_depth_m", "approach_velocity_m_s", "approach_front_velocity_m_s",
                  "approach_bulk_density_kg_m3", "froude", "k_hydrodynamic", "k_hydrodynamic_front", "k_hydrostatic",
                  "k_static_deposit", "barrier_typology"]
RUN_COLUMNS = ["simulated_time_s", "ended_by", "wall_time_s"]
COLUMNS += DESIGN_COLUMNS + RUN_COLUMNS


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def summary_row(out, case, columns):
    """The case's name and status, its summary's values of `columns`, and the summary (None: not run)."""
    row = {"case": case["case"], "status": case["status"]}
    path = os.path.join(out, case["dir"], "summary.json")
    if not os.path.exists(path):
        return row, None
    with open(path) as f:
        s = json.load(f)
    for key in columns:
        if key in s and key not in row:
            row[key] = s[key]
    return row, s


def case_row(out, case):
    row, s = summary_row(out, case, COLUMNS)
    if s is None:
        return row
    r = num(s.get("outlet_width_m")) / num(s.get("outlet_width_over_r")) if num(s.get("outlet_width_over_r")) else math.nan
    if s.get("pile_width_m") and math.isfinite(r) and r > 0:
        row["pile_width_over_r"] = s["pile_width_m"] / r
    row["s_over_r_star"] = s.get("outlet_width_over_r_star")
    piles = s.get("piles") or []
    row["max_pile_normal_force_N"] = max((num(p.get("max_normal_force_N")) for p in piles), default=math.nan)
    # Ē_K: time mean of the mean kinetic energy per grain downstream, from first impact to the end
    series_path = os.path.join(out, case["dir"], "series.csv")
    if os.path.exists(series_path):
        ser = read_csv(series_path)
        t0 = num(s.get("first_impact_time_s"))
        if not math.isfinite(t0) and "downstream_grains" in ser:  # no barrier: first grain past the plane
            past = np.nonzero(ser["downstream_grains"] > 0)[0]
            t0 = float(ser["time_s"][past[0]]) if len(past) else math.nan
        if "downstream_mean_kinetic_energy_J" in ser and len(ser["time_s"]) > 1 and math.isfinite(t0):
            sel = ser["time_s"] >= t0
            if np.count_nonzero(sel) > 1:
                t, e = ser["time_s"][sel], ser["downstream_mean_kinetic_energy_J"][sel]
                row["mean_downstream_kinetic_energy_J"] = float(np.trapz(e, t) / (t[-1] - t[0]))
    return row


def add_closed_ratios(rows):
    free = {num(r.get("slope_deg")): num(r.get("mean_downstream_kinetic_energy_J")) for r in rows
            if r.get("barrier_type") == "none"}
    for r in rows:  # energy-breaking effect: Ē_K relative to the same slope without barrier
        ref = free.get(num(r.get("slope_deg")))
        if ref and r.get("barrier_type") != "none":
            r["kinetic_energy_over_no_barrier"] = num(r.get("mean_downstream_kinetic_energy_J")) / ref
    closed = {num(r.get("slope_deg")): num(r.get("max_global_force_N")) for r in rows if r.get("barrier_type") == "closed"}
    for r in rows:
        fc = closed.get(num(r.get("slope_deg")))
        if fc and r.get("barrier_type") != "closed":
            r["max_over_closed_global_force"] = num(r.get("max_global_force_N")) / fc


def groups(rows, key):
    out = {}
    for r in rows:
        out.setdefault(r.get(key), []).append(r)
    return dict(sorted(out.items(), key=lambda kv: num(kv[0]) if math.isfinite(num(kv[0])) else str(kv[0])))


def save(fig, out, name, images, title):
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=110)
    plt.close(fig)
    images.append((title, name))


def chart_non_retained_vs_s(out, rows, images):
    slits = [r for r in rows if r.get("barrier_type") == "slit" and math.isfinite(num(r.get("non_retained_fraction")))]
    if len({num(r.get("outlet_width_over_r")) for r in slits}) < 2:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for theta, rs in groups(slits, "slope_deg").items():
        rs = sorted(rs, key=lambda r: num(r["outlet_width_over_r"]))
        ax.plot([num(r["outlet_width_over_r"]) for r in rs], [num(r["non_retained_fraction"]) for r in rs], "o-",
                label=f"θ = {theta}°")
    ax.set_xlabel("S / r")
    ax.set_ylabel("non-retained fraction [-]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out, "non_retained_vs_S.png", images, "Non-retained fraction vs S/r")


def chart_arch(out, rows, images):
    pts = [r for r in rows if num(r.get("arch_height_ratio")) > 0 and math.isfinite(num(r.get("t_stop_minus_t0_s")))]
    if not pts:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for mech, rs in groups(pts, "clogging_mechanism").items():
        ax.plot([num(r["t_stop_minus_t0_s"]) for r in rs], [num(r["arch_height_ratio"]) for r in rs], "o", label=mech)
    ax.set_xlabel("t_stop − t0 [s]")
    ax.set_ylabel("H_arch / H_bar [-]")
    ax.set_ylim(0, 1.05)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out, "arch_vs_tstop.png", images, "Arch height vs stopping time")


def series_label(r):
    if r.get("barrier_type") == "sectional":
        return f"config {r.get('barrier_configuration')}"
    if r.get("barrier_type") == "closed":
        return "closed"
    return f"S/r = {fmt(num(r.get('outlet_width_over_r')))}"


def chart_vs_theta(out, rows, images):
    with_theta = [r for r in rows if math.isfinite(num(r.get("max_global_force_N")))]
    if len({num(r.get("slope_deg")) for r in with_theta}) < 2:
        return
    by_label = {}
    for r in with_theta:
        by_label.setdefault(series_label(r), []).append(r)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label, rs in sorted(by_label.items()):
        rs = sorted(rs, key=lambda r: num(r["slope_deg"]))
        ax.plot([num(r["slope_deg"]) for r in rs], [num(r.get("max_pile_normal_force_N")) / 1e3 for r in rs], "o-",
                label=label)
    ax.set_xlabel("slope θ [°]")
    ax.set_ylabel("max normal force on a pile [kN]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out, "pile_force_vs_theta.png", images, "Largest normal force per pile vs slope")

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for label, rs in sorted(by_label.items()):
        rs = sorted(rs, key=lambda r: num(r["slope_deg"]))
        th = [num(r["slope_deg"]) for r in rs]
        if label != "closed":
            axes[0].plot(th, [num(r.get("max_over_closed_global_force")) for r in rs], "o-", label=label)
        # F_static where the deposit came to rest; a case that ended still moving is drawn hollow, over its
        # force at the end (not a static load)
        rest = [str(r.get("deposit_at_rest")).lower() == "true" for r in rs]
        ratio = [num(r.get("max_over_end_global_force")) for r in rs]
        line, = axes[1].plot(th, ratio, "-", label=label)
        axes[1].plot([t for t, a in zip(th, rest) if a], [v for v, a in zip(ratio, rest) if a], "o",
                     color=line.get_color())
        axes[1].plot([t for t, a in zip(th, rest) if not a], [v for v, a in zip(ratio, rest) if not a], "o",
                     mfc="none", color=line.get_color())
    axes[0].set_ylabel("F_max / F_max,closed [-]")
    axes[1].set_ylabel("F_max / F_static [-] (hollow: F_max / F_end, not at rest)")
    for ax in axes:
        ax.set_xlabel("slope θ [°]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, out, "force_ratios_vs_theta.png", images, "Peak force relative to the closed barrier and to the static load")


def fit_energy(out, rows, images):
    """Ē_K = α(θ) S/r + β(θ) P/r over the sectional cases of each slope (least squares, no intercept)."""
    sec = [r for r in rows if r.get("barrier_type") == "sectional" and math.isfinite(num(r.get("mean_downstream_kinetic_energy_J")))]
    fits = []
    for theta, rs in groups(sec, "slope_deg").items():
        if len(rs) < 3:
            continue
        a = np.array([[num(r["outlet_width_over_r"]), num(r["pile_width_over_r"])] for r in rs])
        e = np.array([num(r["mean_downstream_kinetic_energy_J"]) for r in rs])
        coef, *_ = np.linalg.lstsq(a, e, rcond=None)
        pred = a @ coef
        r2 = 1 - np.sum((e - pred) ** 2) / max(np.sum((e - e.mean()) ** 2), 1e-300)
        fits.append((theta, coef[0], coef[1], r2, e, pred, rs))
    if not fits:
        return []
    fig, ax = plt.subplots(figsize=(6, 5))
    for theta, alpha, beta, r2, e, pred, rs in fits:
        ax.plot(e, pred, "o", label=f"θ = {theta}°: α = {alpha:.3g}, β = {beta:.3g}, R² = {r2:.3f}")
        for r, x, y in zip(rs, e, pred):
            ax.annotate(str(r.get("barrier_configuration", "")), (x, y), fontsize=7)
    lim = [0, max(max(f[4].max(), f[5].max()) for f in fits) * 1.1]
    ax.plot(lim, lim, "k--", linewidth=0.8)
    ax.set_xlabel("Ē_K downstream, simulated [J]")
    ax.set_ylabel("α S/r + β P/r [J]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, out, "energy_fit.png", images, "Fit of the mean kinetic energy downstream (sectional barriers)")
    return [(t, a, b, r2) for t, a, b, r2, *_ in fits]


def chart_mixtures(out, rows, images):
    mix = [r for r in rows if math.isfinite(num(r.get("phi_small")))]
    if len({num(r.get("phi_small")) for r in mix}) < 2:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for ax, key, label in ((axes[0], "phi_small", "Φ_small [-]"), (axes[1], "s_over_r_star", "S / r* [-]")):
        pts = sorted(mix, key=lambda r: num(r.get(key)))
        ax.plot([num(r.get(key)) for r in pts], [num(r.get("non_retained_fraction")) for r in pts], "o-")
        ax.set_xlabel(label)
        ax.set_ylabel("non-retained fraction [-]")
        ax.grid(alpha=0.3)
    save(fig, out, "mixtures.png", images, "Mixtures: non-retained fraction vs Φ_small and S/r*")


DEBRIS_COLUMNS = ["case", "status", "mode", "rheology", "solid_fraction", "solid_fraction_actual", "grains",
                  "solid_non_retained_fraction", "fluid_non_retained_fraction", "force_normal_max_over_W_sin_theta",
                  "time_of_force_normal_max_s", "solid_force_normal_max_over_W_sin_theta",
                  "time_of_solid_force_normal_max_s", "fluid_force_normal_max_over_W_sin_theta",
                  "time_of_fluid_force_normal_max_s", "W_tot_sin_theta_N", "W_sin_theta_N",
                  "max_relative_mass_drift"] + DESIGN_COLUMNS + RUN_COLUMNS


def debris_row(out, case):
    """A debris case's summary keys; the fluid alone (V_s/V_box = 0) reports its fluid-only keys, mapped to the
    totals (its force is all fluid)."""
    row, s = summary_row(out, case, DEBRIS_COLUMNS)
    if s is None:
        return row
    if "mode" not in s:  # the fluid alone
        row.update({"mode": "fluid", "solid_fraction_actual": 0.0, "solid_non_retained_fraction": math.nan,
                    "force_normal_max_over_W_sin_theta": s.get("fluid_force_normal_max_over_W_sin_theta"),
                    "time_of_force_normal_max_s": s.get("time_of_fluid_force_normal_max_s"),
                    "solid_force_normal_max_over_W_sin_theta": 0.0})
    return row


def chart_against_fraction(out, by_rheology, curves, ylabel, name, title, images):
    """One line per (curve, rheology) against the actual V_s/V_box; curves: (summary key, label, style)."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for rheology, rs in by_rheology.items():
        rs = sorted(rs, key=lambda r: num(r["solid_fraction_actual"]))
        x = [num(r["solid_fraction_actual"]) for r in rs]
        for key, label, style in curves:
            ax.plot(x, [num(r.get(key)) for r in rs], style, label=f"{label}, {rheology}")
    ax.set_xlabel("V_s / V_box")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out, name, images, title)


def chart_debris(out, rows, images):
    """Non-retained fractions and peak normalised forces against V_s/V_box, one line per rheology."""
    done = [r for r in rows if r.get("status") == "completed"]
    if len({num(r.get("solid_fraction_actual")) for r in done}) < 2:
        return
    by_rheology = groups(done, "rheology")
    chart_against_fraction(out, by_rheology, [("solid_non_retained_fraction", "solid", "o-"),
                                              ("fluid_non_retained_fraction", "fluid", "s--")],
                           "non-retained fraction at the end [-]", "non_retained_vs_solid_fraction.png",
                           "Non-retained fractions vs V_s/V_box", images)
    chart_against_fraction(out, by_rheology, [("force_normal_max_over_W_sin_theta", "total", "o-"),
                                              ("solid_force_normal_max_over_W_sin_theta", "solid", "^:"),
                                              ("fluid_force_normal_max_over_W_sin_theta", "fluid", "s--")],
                           "peak normal force / (W_tot sin θ) [-]", "peak_force_vs_solid_fraction.png",
                           "Peak normal forces vs V_s/V_box", images)


def debris_report(out, cases):
    rows = [debris_row(out, c) for c in cases]
    write_table(out, rows, DEBRIS_COLUMNS)
    images = []
    chart_debris(out, rows, images)
    shown = ["case", "status", "rheology", "solid_fraction_actual", "solid_non_retained_fraction",
             "fluid_non_retained_fraction", "force_normal_max_over_W_sin_theta", "solid_force_normal_max_over_W_sin_theta",
             "fluid_force_normal_max_over_W_sin_theta", "k_hydrodynamic", "wall_time_s"]
    md = report_head(out, rows, shown)
    write_markdown(out, "sweep_report.md", md, images)


SANDPILE_COLUMNS = ["case", "status", "set_up", "seed", "diameter_m", "mu_s_pp", "mu_r_pp", "angle_of_repose_deg",
                    "left_angle_deg", "right_angle_deg", "left_r2", "right_r2", "heap_height_m", "flat_top",
                    "grains_on_plate", "ended_by", "simulated_time_s", "wall_time_s"]


def set_up_of(case_name):
    """A case's set-up: its name without the seed component (the realizations of one set-up share it)."""
    parts = [p for p in case_name.split("__") if not p.startswith("seed=")]
    return "__".join(parts) if parts else "(base case)"


def sandpile_row(out, case):
    row, s = summary_row(out, case, SANDPILE_COLUMNS)
    row["set_up"] = set_up_of(case["case"])
    row["seed"] = case.get("sandpile.seed", "")
    if s is None:
        return row
    for side in ("left", "right"):
        fit = s.get(side) or {}
        row[f"{side}_angle_deg"] = fit.get("angle_deg")
        row[f"{side}_r2"] = fit.get("r2")
    return row


def repose_statistics(rows):
    """Per set-up: the completed heaps' count, mean angle, sample standard deviation and range."""
    stats = []
    for set_up, rs in groups([r for r in rows if r.get("status") == "completed"], "set_up").items():
        a = np.array([num(r.get("angle_of_repose_deg")) for r in rs])
        a = a[np.isfinite(a)]
        if len(a) == 0:
            continue
        sd = float(np.std(a, ddof=1)) if len(a) > 1 else math.nan
        stats.append((set_up, len(a), float(a.mean()), sd, float(a.min()), float(a.max())))
    return stats


def sandpile_report(out, cases):
    rows = [sandpile_row(out, c) for c in cases]
    write_table(out, rows, SANDPILE_COLUMNS)
    stats = repose_statistics(rows)
    images = []
    if stats:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for k, (set_up, _, mean, _, _, _) in enumerate(stats):
            angles = [num(r.get("angle_of_repose_deg")) for r in rows
                      if r.get("set_up") == set_up and r.get("status") == "completed"]
            ax.plot([k] * len(angles), angles, "o", color="tab:blue", alpha=0.6)
            ax.plot([k - 0.2, k + 0.2], [mean, mean], "-", color="black")
        ax.set_xticks(range(len(stats)), [s[0].replace("__", "\n") for s in stats], fontsize=7)
        ax.set_ylabel("angle of repose [°]")
        ax.grid(alpha=0.3)
        save(fig, out, "repose_angle_by_set_up.png", images, "Angle of repose per set-up (dots: heaps, bar: mean)")
    shown = ["case", "status", "angle_of_repose_deg", "left_angle_deg", "right_angle_deg", "heap_height_m",
             "grains_on_plate", "ended_by", "simulated_time_s", "wall_time_s"]
    md = report_head(out, rows, shown)
    if stats:
        md += ["", "## Angle of repose per set-up (the seeds are realizations of one set-up)", "",
               "| set-up | heaps | mean [°] | standard deviation [°] | range [°] |", "|---|---|---|---|---|"]
        md += [f"| {u} | {n} | {m:.2f} | {fmt(sd)} | {lo:.2f} – {hi:.2f} |" for u, n, m, sd, lo, hi in stats]
    write_markdown(out, "sweep_report.md", md, images)


def report_head(out, rows, shown):
    """The report's title, the count of completed cases and the table of the `shown` columns (Markdown lines)."""
    about = {}
    if os.path.exists(os.path.join(out, "sweep.json")):  # written by `sabo sweep`: the sweep's name and case
        with open(os.path.join(out, "sweep.json")) as f:
            about = json.load(f)
    name = about.get("name") or os.path.basename(os.path.normpath(out))
    case = f" — case `{about['case_file']}`" if about.get("case_file") else ""
    md = [f"# Sweep report: {name}{case}", "", f"Folder: `{out}`.", "",
          f"{sum(1 for r in rows if r['status'] == 'completed')} of {len(rows)} cases completed. Full table: "
          "`sweep.csv` (columns in docs/sweeps.md).", "",
          "| " + " | ".join(shown) + " |", "|" + "---|" * len(shown)]
    return md + ["| " + " | ".join(fmt(r.get(k)) for k in shown) + " |" for r in rows]


def write_table(out, rows, columns):
    tmp = os.path.join(out, "sweep.csv.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow(["" if (isinstance(r.get(k), float) and not math.isfinite(r[k])) else r.get(k, "") for k in columns])
    os.replace(tmp, os.path.join(out, "sweep.csv"))


def case_type(out, cases):
    """case.type of the first case that has run ("channel" if none has)."""
    for c in cases:
        path = os.path.join(out, c["dir"], "case_resolved.toml")
        if os.path.exists(path):
            with open(path, "rb") as f:
                return tomllib.load(f).get("case", {}).get("type", "channel")
    return "channel"


def fmt(v):
    if isinstance(v, float):
        return "–" if not math.isfinite(v) else f"{v:.4g}"
    return "–" if v is None else str(v)


def self_test():
    """Known answers (ctest `sweep_report_self_test`): the Ē_K fit recovers α, β of synthetic data;
    the closed-barrier and no-barrier ratios pair cases by slope."""
    import tempfile
    rows = []
    for theta, alpha, beta in ((30, 2.0, 0.5), (40, 3.0, -0.25)):
        for name, s_r, p_r in (("A", 4, 2), ("F", 5, 6.6), ("L", 8, 8.4), ("G", 5, 4.4)):
            rows.append({"case": f"{name}{theta}", "barrier_type": "sectional", "barrier_configuration": name,
                         "slope_deg": theta, "outlet_width_over_r": s_r, "pile_width_over_r": p_r,
                         "mean_downstream_kinetic_energy_J": alpha * s_r + beta * p_r, "max_global_force_N": 10.0})
        rows.append({"case": f"closed{theta}", "barrier_type": "closed", "slope_deg": theta, "max_global_force_N": 40.0})
        rows.append({"case": f"none{theta}", "barrier_type": "none", "slope_deg": theta,
                     "mean_downstream_kinetic_energy_J": 100.0})
    add_closed_ratios(rows)
    with tempfile.TemporaryDirectory() as out:
        fits = fit_energy(out, rows, [])
    got = {t: (a, b) for t, a, b, _ in fits}
    assert abs(got[30][0] - 2.0) < 1e-9 and abs(got[30][1] - 0.5) < 1e-9, got
    assert abs(got[40][0] - 3.0) < 1e-9 and abs(got[40][1] + 0.25) < 1e-9, got
    assert abs(rows[0]["max_over_closed_global_force"] - 0.25) < 1e-12
    assert abs(rows[0]["kinetic_energy_over_no_barrier"] - (2.0 * 4 + 0.5 * 2) / 100.0) < 1e-12
    # sandpiles: the seeds of one set-up grouped, mean and sample standard deviation
    assert set_up_of("diameter_m=0.005__seed=2") == "diameter_m=0.005" and set_up_of("seed=1") == "(base case)"
    heaps = [{"set_up": "a", "status": "completed", "angle_of_repose_deg": x} for x in (20.0, 22.0, 27.0)]
    heaps.append({"set_up": "a", "status": "failed", "angle_of_repose_deg": 90.0})
    (set_up, n, mean, sd, lo, hi), = repose_statistics(heaps)
    assert (set_up, n, lo, hi) == ("a", 3, 20.0, 27.0) and abs(mean - 23.0) < 1e-12
    assert abs(sd - math.sqrt(((20 - 23) ** 2 + (22 - 23) ** 2 + (27 - 23) ** 2) / 2)) < 1e-12
    print("sweep_report self-test passed")


def main():
    if len(sys.argv) == 2 and sys.argv[1] == "--self-test":
        self_test()
        return
    if len(sys.argv) != 2:
        sys.exit("usage: sweep_report.py SWEEP_OUT_DIR | --self-test")
    out = sys.argv[1]
    with open(os.path.join(out, "sweep_cases.csv")) as f:
        cases = list(csv.DictReader(f))
    kind = case_type(out, cases)
    if kind == "debris":
        debris_report(out, cases)
        return
    if kind == "sandpile":
        sandpile_report(out, cases)
        return
    rows = [case_row(out, c) for c in cases]
    add_closed_ratios(rows)
    write_table(out, rows, COLUMNS)

    images = []
    chart_non_retained_vs_s(out, rows, images)
    chart_arch(out, rows, images)
    chart_vs_theta(out, rows, images)
    fits = fit_energy(out, rows, images)
    chart_mixtures(out, rows, images)

    shown = ["case", "status", "slope_deg", "outlet_width_over_r", "barrier_configuration", "non_retained_fraction",
             "max_global_force_N", "max_pile_normal_force_N", "arch_height_ratio", "t_stop_minus_t0_s",
             "clogging_mechanism", "k_hydrodynamic", "wall_time_s"]
    md = report_head(out, rows, shown)
    if fits:
        md += ["", "## Ē_K = α(θ) S/r + β(θ) P/r", "", "| θ [°] | α [J] | β [J] | R² |", "|---|---|---|---|"]
        md += [f"| {t} | {a:.4g} | {b:.4g} | {r2:.3f} |" for t, a, b, r2 in fits]
    write_markdown(out, "sweep_report.md", md, images)


if __name__ == "__main__":
    main()
