#!/usr/bin/env python3
"""An inflow standing on a raised bed feeds the flow it feeds on the plane.

    check_inflow_on_bed.py RAISED_RUN FLAT_RUN BED_LEVEL_M

RAISED_RUN: a run whose channel mesh raises the whole bed by BED_LEVEL_M under the inflow and the reach (its
walls, top and outflow moved with it); FLAT_RUN: the same inflow on the inclined plane. The grains of the
raised run are placed on the relief and roll on its triangles instead of the plane, so the two runs are two
realisations of one flow (their last digits part, and the grains' collisions amplify that). Asserts: every
frame of the raised run has the flat run's grains (no grain lost or made) and none reaches below the raised
bed by more than a tenth of its radius (a contact's overlap, not a grain placed inside the relief); the
grains' kinetic energy at every series row within 2 % of the flat run's largest plus 2 % of itself; the
non-retained fractions within 0.02. Prints "inflow on the bed ok: ..." or the differences, exit 1.
"""
import os
import re
import struct
import sys

from check_divided_grains import kinetic_energy_differs
from check_divided_run import appended_bytes, read_csv, read_summary


def frames(run):
    """(points, radii) of every frame particles.pvd lists."""
    with open(os.path.join(run, "particles.pvd"), encoding="utf-8") as f:
        names = re.findall(r'file="([^"]+)"', f.read())
    out = []
    for name in names:
        raw = open(os.path.join(run, name), "rb").read()
        head = raw[: raw.index(b"<AppendedData")].decode()
        blob = raw[raw.index(b"_", raw.index(b"<AppendedData")) + 1:]
        zlib = "vtkZLibDataCompressor" in head

        def array(label):
            offset = int(re.search(rf'Name="{label}"[^>]*offset="(\d+)"', head).group(1))
            data = appended_bytes(blob, offset, zlib)
            return struct.unpack(f"<{len(data) // 8}d", data)

        out.append((array("points"), array("radius_m")))
    return out


def main():
    raised, flat, level = sys.argv[1], sys.argv[2], float(sys.argv[3])
    problems = []
    lowest = float("inf")
    f_raised, f_flat = frames(raised), frames(flat)
    if [len(r) for _, r in f_raised] != [len(r) for _, r in f_flat]:
        problems.append(f"grains per frame {[len(r) for _, r in f_raised]} vs {[len(r) for _, r in f_flat]}")
    for n, (points, radii) in enumerate(f_raised):
        for i, r in enumerate(radii):
            below = level - (points[3 * i + 2] - r)  # how far the grain reaches below the raised bed
            lowest = min(lowest, (points[3 * i + 2] - r - level) / r)
            if below > 0.1 * r:
                problems.append(f"frame {n}: grain {i} reaches {below:.4f} m below the raised bed")
                break
    h1, rows1 = read_csv(os.path.join(flat, "series.csv"))
    h2, rows2 = read_csv(os.path.join(raised, "series.csv"))
    k = h1.index("grain_kinetic_energy_J")
    if h1 != h2 or len(rows1) != len(rows2):
        problems.append(f"series.csv: {len(rows1)} rows vs {len(rows2)}, columns equal: {h1 == h2}")
    else:
        kinetic_energy_differs(h1, rows1, rows2, problems, " (flat)")
    s1, s2 = read_summary(flat), read_summary(raised)
    for key in ("solid_non_retained_fraction", "fluid_non_retained_fraction"):
        if abs(s1[key] - s2[key]) > 0.02:
            problems.append(f"{key}: {s2[key]} vs {s1[key]} (flat)")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"inflow on the bed ok: {len(f_raised[-1][1])} grains, their lowest {lowest:+.3f} radii from the raised "
          f"bed; kinetic energy at the end {rows2[-1][k]:.1f} J (flat {rows1[-1][k]:.1f} J)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
