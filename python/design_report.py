#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The design comparison of one run as a chart and a markdown section.

    python3 python/design_report.py OUT_DIR

Reads OUT_DIR/design_comparison.csv (written by the run and by `sabo design compare`) and writes
design_comparison.png: every impact formula's force (a bar over its coefficient's range, a dot for a single
value) and the boulder-impact estimates next to the simulated peak normal force. report.py calls
`design_section` for report.md. Needs Debian's python3-matplotlib.
"""
import csv
import math
import os
import sys

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(out):
    path = os.path.join(out, "design_comparison.csv")
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float(text) if text not in ("", None) else math.nan


def plot(out, rows):
    forces = [r for r in rows if r["group"] in ("impact", "boulder")]
    if not forces:
        return None
    fig, ax = plt.subplots(figsize=(8.5, 0.32 * len(forces) + 1.6))
    labels = []
    for k, r in enumerate(forces):
        lo, hi = number(r["predicted_low"]), number(r["predicted_high"])
        color = "tab:blue" if r["group"] == "impact" else "tab:orange"
        if hi > lo:
            ax.plot([lo, hi], [k, k], color=color, linewidth=5, solid_capstyle="butt")
        else:
            ax.plot([lo], [k], "o", color=color)
        labels.append(f"{r['reference']} ({r['coefficient']})")
    peak = number(forces[0]["simulated"])
    if math.isfinite(peak):
        ax.axvline(peak, color="k", linestyle="--", label=f"simulated peak normal force {peak:.3g} kN")
        ax.legend(loc="lower right", fontsize=8)
    ax.set_yticks(range(len(forces)))
    ax.set_yticklabels(labels, fontsize=7)
    ax.invert_yaxis()
    values = [v for r in forces for v in (number(r["predicted_low"]), number(r["predicted_high"]))] + [peak]
    values = [v for v in values if math.isfinite(v) and v > 0]
    if values and max(values) / min(values) > 30:  # several decades: a log axis, its minor ticks labelled too
        ax.set_xscale("log")
        ax.xaxis.set_minor_formatter(matplotlib.ticker.LogFormatterSciNotation(labelOnlyBase=False,
                                                                             minor_thresholds=(3, 1)))
        ax.tick_params(axis="x", which="minor", labelsize=7)
    else:
        ax.set_xlim(left=0)
    ax.set_xlabel("force on the barrier [kN] (blue: debris-flow impact, orange: one boulder)")
    ax.set_title("Design formulas with the approaching flow at the gauge, beside the simulated peak", fontsize=9)
    ax.grid(alpha=0.3, which="both", axis="x")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "design_comparison.png"), dpi=110)
    plt.close(fig)
    return "design_comparison.png"


def design_section(out):
    """Markdown lines and the chart (title, png) of the run's design comparison; ([], None) without one."""
    rows = read_rows(out)
    if not rows:
        return [], None
    png = plot(out, rows)

    def value(r):
        lo, hi = number(r["predicted_low"]), number(r["predicted_high"])
        if not math.isfinite(lo):
            return "–"
        return f"{lo:.4g}" if lo == hi else f"{lo:.4g} – {hi:.4g}"

    md = ["", "## Beside the design formulas", "",
          "The approaching flow measured at the gauge section (docs/design.md) in every formula, next to the "
          "simulated value. `sabo design compare` redraws this with other material constants.", "",
          "| group | reference | formula | coefficient | predicted | simulated | unit | compared |",
          "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["group"] in ("back-calculated", "typology"):
            continue
        sim = number(r["simulated"])
        md.append(f"| {r['group']} | {r['reference']} | {r['formula']} | {r['coefficient']} | {value(r)} | "
                  f"{f'{sim:.4g}' if math.isfinite(sim) else '–'} | {r['unit']} | {r['note']} |")
    md += ["", "| back-calculated coefficient | value | definition |", "|---|---|---|"]
    for r in rows:
        if r["group"] == "back-calculated":
            md.append(f"| {r['reference']} | {value(r)} | {r['formula']} |")
        if r["group"] == "typology":
            md += ["", f"Barrier typology: **{r['note']}**."]
    return md, (("Design formulas beside the simulated peak force", png) if png else None)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: design_report.py OUT_DIR")
    rows = read_rows(sys.argv[1])
    if not rows:
        sys.exit(f"{sys.argv[1]}: no design_comparison.csv")
    plot(sys.argv[1], rows)


if __name__ == "__main__":
    main()
