#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The report's force plots show the peaks the summary reports: for each figure, every reported peak is a
plotted point and nothing plotted exceeds the largest of them (a curve of series rows missed a one-step
spike: pile_forces.png peaked at ~14 kN beside a table saying 20.46 kN).

    check_report_extremes.py PYTHON_DIR channel|debris RUN_DIR
"""
import json
import math
import os
import sys


def main() -> int:
    python_dir, kind, out = sys.argv[1], sys.argv[2], sys.argv[3]
    sys.path.insert(0, python_dir)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.figure
    import matplotlib.pyplot as plt

    figures = {}
    save = matplotlib.figure.Figure.savefig

    def keep(fig, path, *args, **kwargs):
        figures[os.path.basename(str(path))] = fig
        return save(fig, path, *args, **kwargs)

    matplotlib.figure.Figure.savefig = keep
    plt.close = lambda *args, **kwargs: None  # the figures stay to be read
    module = __import__("report" if kind == "channel" else "debris_report")
    sys.argv = ["report", out]
    module.main()
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)

    if kind == "channel":
        expected = {"force_history.png": [s["max_global_force_N"] / 1e3, s["max_normal_force_N"] / 1e3],
                    "pile_forces.png": [p["max_normal_force_N"] / 1e3 for p in s["piles"]]}
    else:
        keys = ["force_normal", "solid_force_normal"] + (["fluid_force_normal"] if s["mode"] == "coupled" else [])
        expected = {"forces.png": [s[f"{k}_max_over_W_sin_theta"] for k in keys]}
    failures = 0
    for name, peaks in expected.items():
        ys = [float(y) for line in figures[name].axes[0].lines for y in line.get_ydata()
              if isinstance(y, (int, float)) or hasattr(y, "dtype")]
        ys = [y for y in ys if math.isfinite(y)]
        top = max(ys)
        missing = [p for p in peaks if not any(abs(y - p) <= 1e-9 * max(1.0, abs(p)) for y in ys)]
        ok = not missing and abs(top - max(peaks)) <= 1e-9 * max(1.0, abs(top))
        failures += not ok
        print(f"{name}: plotted max {top:.6g}, reported peaks {', '.join(f'{p:.6g}' for p in peaks)}"
              f"{'' if not missing else f'; not plotted: {missing}'} -> {'ok' if ok else 'MISMATCH'}")
    print("plotted extremes equal the reported ones" if failures == 0 else f"{failures} figure(s) disagree")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
