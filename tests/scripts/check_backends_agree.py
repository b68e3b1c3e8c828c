#!/usr/bin/env python3
"""Two runs of one case on the two lattice backends (CPU, OpenCL) agree: every series.csv column (and
grains_series.csv's, where the case writes one), row by
row, to float64 round-off — within 1e-9 of the largest magnitude among the columns of the same unit (the
name's last part: every force in newtons against the largest force, so a component that is zero up to
round-off, such as the cross-channel force of a symmetric flow, is measured against the forces in play,
not against itself) plus 1e-12 — the same number of rows, the summary's status, and every fluid frame
(the same times; each cell array within 1e-6 of that quantity's largest magnitude over the frames: frames
hold float32, whose last bit may round either way).

With --float32 (both runs store float32: the CPU lattice computes its surface cells in double, the device
all in float32, and the free surface amplifies the difference): the series within 1e-4 of each unit's
largest magnitude plus 1e-6 (float32's round-off of quantities that are round-off themselves: the mass
drift is ~3e-8); in the frames the cell types identical and each other array's mean absolute difference
within 1e-3 of that quantity's largest magnitude (a few surface cells' λ differ by up to 1 %).

A run divided among MPI ranks (frames as .pvti pieces) is compared through its pieces joined: a slab
on a device sums its orphan mass over its own cells, so its state may differ from the whole lattice's
by round-off, which these tolerances state.

With --series-only the frames are not compared: two runs of one flow on lattices of different shapes (the
same channel between meshed side walls in a wider domain, and in the box of its width).

usage: check_backends_agree.py [--float32] [--series-only] RUN_A RUN_B
"""
import csv
import json
import os
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import xml.etree.ElementTree as ET  # noqa: E402

from check_divided_run import frames, joined, read_vti  # noqa: E402

RELATIVE, ABSOLUTE = 1e-9, 1e-12


def rows(run, name="series.csv"):
    with open(Path(run) / name, newline="") as f:
        return list(csv.DictReader(f))


def compare_rows(a, b, relative, absolute):
    """The worst difference of two tables as a share of the tolerance, and where it is."""
    worst, where = 0.0, ""
    unit = {key: key.rsplit("_", 1)[-1] for key in a[0]}
    scale = {}
    for key in a[0]:
        largest = max(abs(float(r[key])) for r in a + b)
        scale[unit[key]] = max(scale.get(unit[key], 0.0), largest)
    for i, (ra, rb) in enumerate(zip(a, b)):
        for key in ra:
            x, y = float(ra[key]), float(rb[key])
            excess = abs(x - y) / (relative * scale[unit[key]] + absolute)
            if excess > worst:
                worst, where = excess, f"row {i} {key}: {x!r} vs {y!r}"
    return worst, where


def frame_arrays(run, file):
    """{name: (components, values)} of a frame: a .vti, or a .pvti's pieces joined along x."""
    path = os.path.join(run, file)
    if not file.endswith(".pvti"):
        return read_vti(path)[1]
    pieces = len(ET.parse(path).getroot().find("PImageData").findall("Piece"))
    problems = []
    arrays = joined(path, pieces, problems)
    if problems:
        raise SystemExit(f"FAIL: {problems}")
    return {name: (None, values) for name, values in arrays.items()}


def main():
    args = sys.argv[1:]
    single, series_only = "--float32" in args, "--series-only" in args
    a_dir, b_dir = [a for a in args if a not in ("--float32", "--series-only")]
    relative, absolute = (1e-4, 1e-6) if single else (RELATIVE, ABSOLUTE)
    a, b = rows(a_dir), rows(b_dir)
    if len(a) != len(b) or not a:
        print(f"FAIL: {len(a)} rows against {len(b)}")
        return 1
    worst, where = compare_rows(a, b, relative, absolute)
    # runs with grains: their own series (positions, velocities, forces) in the same way
    if (Path(a_dir) / "grains_series.csv").exists():
        ga, gb = rows(a_dir, "grains_series.csv"), rows(b_dir, "grains_series.csv")
        if len(ga) != len(gb) or not ga:
            print(f"FAIL: grains_series.csv {len(ga)} rows against {len(gb)}")
            return 1
        grain_worst, grain_where = compare_rows(ga, gb, relative, absolute)
        print(f"grains_series.csv: {len(ga)} rows; worst difference {grain_worst:.3g} of the tolerance ({grain_where})")
        worst = max(worst, grain_worst)
    status = [json.load(open(Path(d) / "summary.json"))["status"] for d in (a_dir, b_dir)]
    print(f"{len(a)} rows, {len(a[0])} columns; worst difference {worst:.3g} of the tolerance ({where}); status {status}")
    if series_only:
        if worst > 1.0 or status[0] != status[1]:
            print("FAIL")
            return 1
        print("backends agree (series)")
        return 0
    frames_a, frames_b = frames(a_dir), frames(b_dir)
    frame_worst, frame_where = 0.0, ""
    if [t for t, _ in frames_a] != [t for t, _ in frames_b] or not frames_a:
        print(f"FAIL: frames at {[t for t, _ in frames_a]} against {[t for t, _ in frames_b]}")
        return 1
    loaded = []
    scale = {}
    for (t, file_a), (_, file_b) in zip(frames_a, frames_b):
        arrays_a, arrays_b = frame_arrays(a_dir, file_a), frame_arrays(b_dir, file_b)
        loaded.append((t, arrays_a, arrays_b))
        for name, (_, values) in list(arrays_a.items()) + list(arrays_b.items()):
            scale[name] = max(scale.get(name, 0.0), max(abs(v) for v in values))
    for t, arrays_a, arrays_b in loaded:
        for name, (_, values_a) in arrays_a.items():
            values_b = arrays_b[name][1]
            if single and name != "cell_type":
                mean = sum(abs(va - vb) for va, vb in zip(values_a, values_b)) / max(len(values_a), 1)
                excess = mean / (1e-3 * scale[name] + 1e-30)
                if excess > frame_worst:
                    frame_worst, frame_where = excess, f"t = {t} {name}: mean difference {mean:.3g}"
                continue
            for va, vb in zip(values_a, values_b):
                excess = abs(va - vb) / (1e-6 * scale[name] + 1e-30)
                if excess > frame_worst:
                    frame_worst, frame_where = excess, f"t = {t} {name}: {va!r} vs {vb!r}"
    print(f"{len(frames_a)} frames; worst difference {frame_worst:.3g} of the tolerance ({frame_where})")
    if worst > 1.0 or status[0] != status[1] or frame_worst > 1.0:
        print("FAIL")
        return 1
    print("backends agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
