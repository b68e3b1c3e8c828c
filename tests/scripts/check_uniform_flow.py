#!/usr/bin/env python3
"""A steady inflow reaches the open-channel flow's depth, and what entered is the hydrograph's volume.

    check_uniform_flow.py RUN DISCHARGE_M3_S WIDTH_M VISCOSITY_PA_S DENSITY_KG_M3 SLOPE_DEG X0_M X1_M TOLERANCE
    check_uniform_flow.py RUN --volume-only

Reads the run's last fluid frame (frames/fluid_*.vti, raw appended data) and summary.json. The depth is the
fluid's column (the fill fractions summed over the cells' height) averaged across the channel and over
X0…X1; the reference is the laminar Newtonian flow in an open rectangular channel, no slip on the bed and
both walls, free surface on top: half the flow of a W × 2h duct driven by ρ g sin θ,
Q = ½ (g sin θ / ν) W (2h)³/12 [1 − 192 (2h)/(π⁵ W) Σ_{n odd} tanh(nπW/(4h))/n⁵] (2h ≤ W, else W and 2h swap),
solved for h. Asserts the depth within TOLERANCE (relative) of it, and the inflow's volume within 1 % of the
hydrograph's integral. Prints "uniform flow ok: ..." or the differences, exit 1.
"""
import glob
import json
import math
import os
import re
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_divided_run import appended_bytes  # noqa: E402


def read_fill(path):
    raw = open(path, "rb").read()
    head = raw[: raw.index(b"<AppendedData")].decode()
    ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
    nx, ny, nz = ext[1] - ext[0], ext[3] - ext[2], ext[5] - ext[4]
    dx = float(re.search(r'Spacing="([^ ]+)', head).group(1))
    blob = raw[raw.index(b"_", raw.index(b"<AppendedData")) + 1:]
    m = re.search(r'Name="fill_fraction" NumberOfComponents="1" format="appended" offset="(\d+)"', head)
    data = appended_bytes(blob, int(m.group(1)), "vtkZLibDataCompressor" in head)
    values = struct.unpack(f"<{len(data) // 4}f", data)
    return values, nx, ny, nz, dx


def open_channel_discharge(h, width, nu, g_sin):
    a, b = width, 2.0 * h
    if b > a:
        a, b = b, a
    series = sum(math.tanh(n * math.pi * a / (2.0 * b)) / n**5 for n in range(1, 400, 2))
    return 0.5 * (g_sin / nu) * a * b**3 / 12.0 * (1.0 - 192.0 * b / (math.pi**5 * a) * series)


def normal_depth(q, width, nu, g_sin):
    lo, hi = 1e-6, 100.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if open_channel_discharge(mid, width, nu, g_sin) < q:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    run = sys.argv[1]
    if sys.argv[2] == "--volume-only":  # a hydrograph that rises and falls: what entered, its integral
        with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
            s = json.load(f)
        d = s["inflow_volume_relative_difference"]
        if abs(d) > 0.01 or s["inflow_hydrograph_volume_m3"] <= 0.0:
            print(f"inflow {s['inflow_volume_m3']} of {s['inflow_hydrograph_volume_m3']} m3 ({d:+.4f})")
            return 1
        print(f"inflow ok: {s['inflow_volume_m3']:.5f} of {s['inflow_hydrograph_volume_m3']:.5f} m3 ({d:+.5f}); "
              f"mass drift {s['max_relative_mass_drift']:.2g}")
        return 0
    q, width, mu, rho, slope, x0, x1, tol = (float(v) for v in sys.argv[2:10])
    frames = sorted(glob.glob(os.path.join(run, "frames", "fluid_*.vti")))
    fill, nx, ny, nz, dx = read_fill(frames[-1])
    depths = []
    for i in range(int(x0 / dx), int(x1 / dx)):
        across = [sum(fill[(k * ny + j) * nx + i] for k in range(nz)) * dx for j in range(ny)]
        depths.append(sum(across) / ny)
    depth = sum(depths) / len(depths)
    reference = normal_depth(q, width, mu / rho, 9.81 * math.sin(math.radians(slope)))
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        s = json.load(f)
    problems = []
    if abs(depth - reference) > tol * reference:
        problems.append(f"depth {depth:.4f} m over X {x0}…{x1} m, the open channel's {reference:.4f} m")
    if min(depths) < (1.0 - 2.0 * tol) * reference or max(depths) > (1.0 + 2.0 * tol) * reference:
        problems.append(f"not uniform: {min(depths):.4f}…{max(depths):.4f} m")
    if abs(s["inflow_volume_relative_difference"]) > 0.01:
        problems.append(f"inflow volume off by {s['inflow_volume_relative_difference']:.4f}")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"uniform flow ok: depth {depth:.4f} m ({min(depths):.4f}…{max(depths):.4f}) against {reference:.4f} m; "
          f"inflow {s['inflow_volume_m3']:.4f} of {s['inflow_hydrograph_volume_m3']:.4f} m3")
    return 0


if __name__ == "__main__":
    sys.exit(main())
