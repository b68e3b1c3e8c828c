# SPDX-License-Identifier: MIT
"""Helpers shared by report.py and sweep_report.py."""
import json
import math
import os
import sys

import numpy as np


def read_csv(path):
    """Columns of a CSV with a header line, as a dict of float arrays ('#' lines skipped, empty = NaN)."""
    with open(path) as f:
        lines = [ln for ln in f.read().splitlines() if ln and not ln.startswith("#")]
    header = lines[0].split(",")
    rows = [ln.split(",") for ln in lines[1:]]
    cols = {}
    for k, name in enumerate(header):
        cols[name] = np.array([float(r[k]) if r[k] != "" else math.nan for r in rows])
    return cols


def write_markdown(out, name, lines, images):
    """Appends one section per (title, png) to `lines` and writes out/name atomically."""
    for title, png in images:
        lines += ["", f"## {title}", "", f"![{title}]({png})"]
    tmp = os.path.join(out, name + ".tmp")
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, os.path.join(out, name))


def run_folder_summary(script):
    """The output folder named on the command line (`script OUT_DIR`) and its summary.json."""
    if len(sys.argv) != 2:
        sys.exit(f"usage: {script} OUT_DIR")
    out = sys.argv[1]
    with open(os.path.join(out, "summary.json")) as f:
        return out, json.load(f)
