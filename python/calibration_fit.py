#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Fit of the calibration law to a `sabo calibrate --sweep` folder (reference case C1, docs/calibration.md).

    python3 python/calibration_fit.py SWEEP_DIR      (run by sabo calibrate --sweep)
    python3 python/calibration_fit.py --self-test    (recovers the reference constants from synthetic data)

Per μ_r, φ = sqrt(a μ_s) is fitted by least squares in φ (sqrt(a) = Σ φ sqrt(μ_s) / Σ μ_s); then
a(μ_r) = k μ_r up to a break μ_r* and a = c above it (the break chosen among the grid values by least
squares, or none). The reference law is k = 151.7², c = 53.0², μ_r* = 0.12.
Writes calibration_points.csv, calibration_residuals.csv, calibration_fit.json, calibration_fit.md and
calibration_contour.png (measured φ over (μ_s, μ_r), the fitted law, the reference law and Zhou et al.'s).
"""
import csv
import json
import math
import os
import sys

SPEC_K, SPEC_C, SPEC_BREAK = 151.7 ** 2, 53.0 ** 2, 0.12


def spec_law(mu_s, mu_r):
    return 151.7 * math.sqrt(mu_r * mu_s) if mu_r <= SPEC_BREAK else 53.0 * math.sqrt(mu_s)


def zhou_law(mu_s_pp, mu_s_pw, mu_r_pp, mu_r_pw, d_mm):
    """Zhou et al. (2002); μ_r as lengths in mm: μ_r A_r with A_r = d/4 (pair), d/2 (wall)."""
    if mu_r_pp <= 0.0:
        return math.nan
    return (68.61 * mu_s_pp ** 0.27 * mu_s_pw ** 0.22 * (mu_r_pp * d_mm / 4) ** 0.06 *
            (mu_r_pw * d_mm / 2) ** 0.12 * d_mm ** -0.2)


def fit(points):
    """points: list of (mu_s, mu_r, phi). Returns the fit as a dict."""
    by_r = {}
    for mu_s, mu_r, phi in points:
        by_r.setdefault(mu_r, []).append((mu_s, phi))
    per = []
    for mu_r in sorted(by_r):
        pts = by_r[mu_r]
        sqrt_a = sum(phi * math.sqrt(s) for s, phi in pts) / sum(s for s, _ in pts)
        rms = math.sqrt(sum((phi - sqrt_a * math.sqrt(s)) ** 2 for s, phi in pts) / len(pts))
        per.append({"mu_r": mu_r, "a": sqrt_a ** 2, "sqrt_a": sqrt_a, "rms_deg": rms, "cases": len(pts)})
    best = None
    mrs = [p["mu_r"] for p in per]
    for brk in mrs + [math.inf]:
        low = [p for p in per if p["mu_r"] <= brk]
        high = [p for p in per if p["mu_r"] > brk]
        den = sum(p["mu_r"] ** 2 for p in low)
        if den <= 0.0:
            continue
        k = sum(p["a"] * p["mu_r"] for p in low) / den
        c = sum(p["a"] for p in high) / len(high) if high else math.nan
        sse = sum((p["a"] - k * p["mu_r"]) ** 2 for p in low) + sum((p["a"] - c) ** 2 for p in high)
        if best is None or sse < best["sse"] - 1e-12 * max(1.0, sse):
            best = {"k": k, "c": c, "break_mu_r": brk, "sse": sse}
    if best is None:
        raise ValueError("need at least one mu_r > 0")

    def law(mu_s, mu_r):
        a = best["k"] * mu_r if mu_r <= best["break_mu_r"] else best["c"]
        return math.sqrt(max(a, 0.0) * mu_s)

    res = [(s, r, phi, law(s, r), phi - law(s, r)) for s, r, phi in points]
    rms = math.sqrt(sum(e[4] ** 2 for e in res) / len(res))
    return {"per_mu_r": per, "k": best["k"], "sqrt_k": math.sqrt(best["k"]), "c": best["c"],
            "sqrt_c": math.sqrt(best["c"]) if not math.isnan(best["c"]) else math.nan,
            "break_mu_r": best["break_mu_r"] if math.isfinite(best["break_mu_r"]) else None,
            "rms_deg": rms, "residuals": res, "law": law}


def read_points(out):
    points, rows = [], []
    with open(os.path.join(out, "sweep_cases.csv")) as f:
        for row in csv.DictReader(f):
            summary = os.path.join(out, row["dir"], "summary.json")
            if row["status"] != "completed" or not os.path.exists(summary):
                continue
            with open(summary) as g:
                s = json.load(g)
            phi = s.get("angle_of_repose_deg")
            if phi is None:
                continue
            mu_s, mu_r = float(row["contact.particle_particle.mu_s"]), float(row["contact.particle_particle.mu_r"])
            points.append((mu_s, mu_r, phi))
            rows.append([mu_s, mu_r, phi, s["left"]["angle_deg"], s["right"]["angle_deg"], s["left"]["r2"],
                         s["right"]["r2"], int(s["flat_top"]), s["particles"], s["diameter_m"]])
    return points, rows


def write_csv(path, header, rows):
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    os.replace(tmp, path)


def plot(out, points, result, d_mm):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    ms = np.array([p[0] for p in points])
    mr = np.array([p[1] for p in points])
    ph = np.array([p[2] for p in points])
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    if len(set(ms)) >= 2 and len(set(mr)) >= 2 and len(points) >= 4:
        cf = ax.tricontourf(ms, mr, ph, levels=12, cmap="viridis")
        fig.colorbar(cf, ax=ax, label="measured angle of repose [deg]")
    ax.scatter(ms, mr, c="w", edgecolors="k", s=14, zorder=3)
    gs, gr = np.meshgrid(np.linspace(max(ms.min(), 1e-3), ms.max(), 60), np.linspace(mr.min(), mr.max(), 60))
    levels = list(range(5, 60, 5))
    for fn, style, label in ((result["law"], "-", "fitted law"), (spec_law, "--", "reference law"),
                             (lambda s, r: zhou_law(s, s, r, 2 * r, d_mm), ":", "Zhou et al. 2002")):
        z = np.vectorize(fn)(gs, gr)
        cs = ax.contour(gs, gr, z, levels=levels, colors="w" if style == "-" else "k", linestyles=style,
                        linewidths=1.0)
        ax.clabel(cs, fontsize=7, fmt="%d°")
        ax.plot([], [], style, color="grey", label=label)
    ax.set_xlabel("μ_s (particle–particle = particle–wall)")
    ax.set_ylabel("μ_r (particle–particle; wall 2 μ_r)")
    ax.set_title(f"Angle of repose over (μ_s, μ_r), d = {d_mm:g} mm")
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "calibration_contour.png"), dpi=130)
    plt.close(fig)


def report(out):
    points, rows = read_points(out)
    if not points:
        sys.exit("no completed sandpile with an angle in " + out)
    write_csv(os.path.join(out, "calibration_points.csv"),
              ["mu_s", "mu_r", "angle_deg", "left_deg", "right_deg", "left_r2", "right_r2", "flat_top", "particles",
               "diameter_m"], rows)
    result = fit(points)
    write_csv(os.path.join(out, "calibration_residuals.csv"),
              ["mu_s", "mu_r", "measured_deg", "fitted_deg", "residual_deg", "spec_law_deg"],
              [list(e) + [spec_law(e[0], e[1])] for e in result["residuals"]])
    summary = {k: result[k] for k in ("k", "sqrt_k", "c", "sqrt_c", "break_mu_r", "rms_deg", "per_mu_r")}
    summary["spec"] = {"sqrt_k": 151.7, "sqrt_c": 53.0, "break_mu_r": SPEC_BREAK}
    summary["cases"] = len(points)
    tmp = os.path.join(out, "calibration_fit.json.tmp")
    with open(tmp, "w") as f:
        json.dump(summary, f, indent=1, default=lambda x: None)
    os.replace(tmp, os.path.join(out, "calibration_fit.json"))
    d_mm = rows[0][9] * 1000.0
    try:
        plot(out, points, result, d_mm)
        images = [("Angle of repose over (μ_s, μ_r)", "calibration_contour.png")]
    except ImportError:
        images = []
    brk = result["break_mu_r"]
    lines = ["# Calibration sweep", "",
             f"{len(points)} sandpiles, {rows[0][8]} grains of d = {d_mm:g} mm; particle–wall μ_s = μ_s, μ_r = 2 μ_r.", "",
             "| constant | fitted | reference law |", "|---|---|---|",
             f"| sqrt(k): φ = sqrt(k μ_r μ_s) below the break | {result['sqrt_k']:.1f} | 151.7 |",
             f"| sqrt(c): φ = sqrt(c μ_s) above the break | {result['sqrt_c']:.1f} | 53.0 |",
             f"| break μ_r* | {brk if brk is not None else 'none'} | 0.12 |",
             f"| RMS residual | {result['rms_deg']:.2f}° | |", "",
             "| μ_r | sqrt(a) [deg] | RMS of φ = sqrt(a μ_s) [deg] | cases |", "|---|---|---|---|"]
    lines += [f"| {p['mu_r']:g} | {p['sqrt_a']:.2f} | {p['rms_deg']:.2f} | {p['cases']} |" for p in result["per_mu_r"]]
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from report_common import write_markdown
    write_markdown(out, "calibration_fit.md", lines, images)
    print(f"fitted: sqrt(k) = {result['sqrt_k']:.1f} (reference 151.7), sqrt(c) = {result['sqrt_c']:.1f} (reference 53.0), "
          f"break {brk} (reference 0.12), RMS {result['rms_deg']:.2f} deg")


def self_test():
    grid = [(s / 20.0, r / 50.0) for s in range(2, 21) for r in range(0, 11)]
    pts = [(s, r, spec_law(s, r)) for s, r in grid]
    res = fit(pts)
    assert abs(res["sqrt_k"] - 151.7) < 1e-9, res["sqrt_k"]
    assert abs(res["sqrt_c"] - 53.0) < 1e-9, res["sqrt_c"]
    assert abs(res["break_mu_r"] - 0.12) < 1e-12, res["break_mu_r"]
    assert res["rms_deg"] < 1e-9
    # noise of ±0.5° moves the constants by little
    import random
    rnd = random.Random(1)
    noisy = fit([(s, r, phi + rnd.uniform(-0.5, 0.5)) for s, r, phi in pts])
    assert abs(noisy["sqrt_k"] - 151.7) < 2.0 and abs(noisy["sqrt_c"] - 53.0) < 1.0, noisy
    print("calibration_fit self-test passed")


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] == "--self-test":
        self_test()
    elif len(sys.argv) == 2:
        report(sys.argv[1])
    else:
        sys.exit(__doc__)
