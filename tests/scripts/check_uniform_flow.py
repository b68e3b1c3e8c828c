#!/usr/bin/env python3
"""A steady inflow reaches the open-channel flow's depth, and what entered is the hydrograph's volume.

    check_uniform_flow.py RUN DISCHARGE_M3_S WIDTH_M VISCOSITY_PA_S DENSITY_KG_M3 SLOPE_DEG X0_M X1_M TOLERANCE
    check_uniform_flow.py RUN --volume-only
    check_uniform_flow.py RUN ... X1_M --whole-cells [--bingham YIELD_STRESS_PA] [--last-frames K]
    check_uniform_flow.py RUN ... TOLERANCE [--bingham YIELD_STRESS_PA] [--last-frames K]

Reads the run's last fluid frame (frames/fluid_*.vti, raw appended data) and summary.json, or the mean of its
last K frames (--last-frames K: a steady flow's depth at each station is its mean in time; the lattice's
surface moves in whole cells, in patches that travel down the channel). The depth is the fluid's column
(the fill fractions summed over the cells' height) averaged across the channel and over X0…X1; the reference
is the laminar Newtonian flow in an open rectangular channel, no slip on the bed and both walls, free surface
on top: half the flow of a W × 2h duct driven by ρ g sin θ,
Q = ½ (g sin θ / ν) W (2h)³/12 [1 − 192 (2h)/(π⁵ W) Σ_{n odd} tanh(nπW/(4h))/n⁵] (2h ≤ W, else W and 2h swap),
solved for h. Asserts the depth within TOLERANCE (relative) of it and every station within twice that, and the
inflow's volume within 1 % of the hydrograph's integral. Prints "uniform flow ok: ..." or the differences,
exit 1.

With --whole-cells in TOLERANCE's place the depth is held to what the lattice can do instead: its free surface pins a uniform
flow's depth to whole cells (docs/lbm.md, "The free surface's depth": it stands at N or N + 1 cells, or
alternates between them in patches, where N Δx <= h <= (N + 1) Δx brackets the reference h), so every
station's depth must lie in that bracket, give or take a tenth of a cell (the surface cells' fill).

    check_uniform_flow.py RUN ... TOLERANCE --bingham YIELD_STRESS_PA

A Bingham fluid (plastic viscosity VISCOSITY_PA_S) has no closed form in a rectangular channel: the reference
is the same steady flow solved on the cross-section (finite volumes, half the width by symmetry, no slip on
the bed and the wall, no stress at the surface) with the lattice's law, η = η0 + τ0/γ̇ capped at the
lattice's largest relaxation time (τ_max = 1.8: η_max = ρ (τ_max − ½)/3 Δx²/Δt, from the run's Δx and Δt),
iterated to convergence on 16 and 32 cells across the half width and extrapolated (the discretisation's error
is first order), its depth found by the secant method.
"""
import glob
import json
import math
import os
import re
import struct
import sys
import tomllib

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


def bingham_discharge(h, width, eta0, tau0, eta_max, rho, g_sin, n):
    """Q of the steady flow of depth h on n cells across the half width (finite volumes, Picard iterations on
    the apparent viscosity, harmonic means at the faces)."""
    import numpy as np
    ny, nz = n, max(8, int(round(n * h / (width / 2))))
    dy, dz = (width / 2) / ny, h / nz
    size = ny * nz
    u, eta = np.zeros(size), np.full(size, float(eta0))
    for sweep in range(400):
        e = eta.reshape(nz, ny)
        a = np.zeros((size, size))
        b = np.full(size, -rho * g_sin * dy * dz)
        for k in range(nz):
            for j in range(ny):
                p = k * ny + j
                for dj, dk, area, step in ((-1, 0, dz, dy), (1, 0, dz, dy), (0, -1, dy, dz), (0, 1, dy, dz)):
                    jj, kk = j + dj, k + dk
                    if jj < 0 or kk < 0:  # the wall (y = 0) or the bed: no slip half a cell away
                        a[p, p] -= e[k, j] * area / (step / 2)
                    elif jj < ny and kk < nz:  # (the channel's middle and the surface carry no stress)
                        f = 2 * e[k, j] * e[kk, jj] / (e[k, j] + e[kk, jj])
                        a[p, p] -= f * area / step
                        a[p, kk * ny + jj] += f * area / step
        new = np.linalg.solve(a, b)
        grid = new.reshape(nz, ny)
        across = np.concatenate([-grid[:, :1], grid, grid[:, -1:]], axis=1)  # wall, symmetry
        up = np.concatenate([-grid[:1, :], grid, grid[-1:, :]], axis=0)  # bed, free surface
        rate = np.hypot((across[:, 2:] - across[:, :-2]) / (2 * dy), (up[2:, :] - up[:-2, :]) / (2 * dz))
        target = np.minimum(eta0 + tau0 / np.maximum(rate, 1e-12), eta_max).ravel()
        change = np.max(np.abs(new - u)) / max(np.max(np.abs(new)), 1e-30)
        u, eta = new, 0.5 * (eta + target)
        if change < 1e-8 and sweep > 3:
            break
    return 2.0 * float(np.sum(u)) * dy * dz


def bingham_depth(q, width, eta0, tau0, eta_max, rho, g_sin, first_guess):
    def excess(h):  # extrapolated from 16 and 32 cells across the half width
        coarse = bingham_discharge(h, width, eta0, tau0, eta_max, rho, g_sin, 16)
        fine = bingham_discharge(h, width, eta0, tau0, eta_max, rho, g_sin, 32)
        return 2.0 * fine - coarse - q
    h0, h1 = first_guess, 1.2 * first_guess
    f0, f1 = excess(h0), excess(h1)
    for _ in range(30):
        h2 = h1 - f1 * (h1 - h0) / (f1 - f0)
        if abs(h2 - h1) < 1e-6 * h1:
            return h2
        h0, f0, h1, f1 = h1, f1, h2, excess(h2)
    return h1


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
    q, width, mu, rho, slope, x0, x1 = (float(v) for v in sys.argv[2:9])
    whole_cells = sys.argv[9] == "--whole-cells"
    tol = None if whole_cells else float(sys.argv[9])
    options = dict(zip(sys.argv[10::2], sys.argv[11::2]))
    unknown = set(options) - {"--bingham", "--last-frames"}
    if unknown or len(sys.argv[10:]) % 2:
        print(f"unknown or incomplete options {sys.argv[10:]}: --bingham YIELD_STRESS_PA, --last-frames K")
        return 2
    yield_stress = float(options["--bingham"]) if "--bingham" in options else None
    last = int(options.get("--last-frames", 1))
    frames = sorted(glob.glob(os.path.join(run, "frames", "fluid_*.vti")))[-last:]
    fill, nx, ny, nz, dx = read_fill(frames[0])
    for later in frames[1:]:
        fill = [a + b for a, b in zip(fill, read_fill(later)[0])]
    fill = [v / len(frames) for v in fill]
    depths = []
    for i in range(int(x0 / dx), int(x1 / dx)):
        across = [sum(fill[(k * ny + j) * nx + i] for k in range(nz)) * dx for j in range(ny)]
        depths.append(sum(across) / ny)
    depth = sum(depths) / len(depths)
    g_sin = 9.81 * math.sin(math.radians(slope))
    reference = normal_depth(q, width, mu / rho, g_sin)
    if yield_stress is not None:
        with open(os.path.join(run, "case_resolved.toml"), "rb") as f:
            dt = tomllib.load(f)["lattice"]["dt_s"]
        eta_max = rho * (1.8 - 0.5) / 3.0 * dx * dx / dt
        newtonian = reference
        reference = bingham_depth(q, width, mu, yield_stress, eta_max, rho, g_sin, newtonian)
        print(f"Bingham reference: tau0 {yield_stress:g} Pa, eta0 {mu:g} Pa s, eta_max {eta_max:.4g} Pa s: depth "
              f"{reference:.4f} m (Newtonian {newtonian:.4f} m)")
    with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
        s = json.load(f)
    problems = []
    if whole_cells:
        low = (math.floor(reference / dx) - 0.1) * dx
        high = (math.ceil(reference / dx) + 0.1) * dx
        if min(depths) < low or max(depths) > high:
            problems.append(f"depth {min(depths):.4f}…{max(depths):.4f} m over X {x0}…{x1} m outside the whole "
                            f"cells {low:.4f}…{high:.4f} m that bracket the open channel's {reference:.4f} m")
    else:
        if abs(depth - reference) > tol * reference:
            problems.append(f"depth {depth:.4f} m over X {x0}…{x1} m, the open channel's {reference:.4f} m")
        if min(depths) < (1.0 - 2.0 * tol) * reference or max(depths) > (1.0 + 2.0 * tol) * reference:
            problems.append(f"not uniform: {min(depths):.4f}…{max(depths):.4f} m")
    if abs(s["inflow_volume_relative_difference"]) > 0.01:
        problems.append(f"inflow volume off by {s['inflow_volume_relative_difference']:.4f}")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"uniform flow ok: depth {depth:.4f} m ({min(depths):.4f}…{max(depths):.4f}; {len(frames)} frames) "
          f"against {reference:.4f} m ({100 * (depth / reference - 1):+.1f} %, {(depth - reference) / dx:+.2f} cells); "
          f"inflow {s['inflow_volume_m3']:.4f} of {s['inflow_hydrograph_volume_m3']:.4f} m3")
    return 0


if __name__ == "__main__":
    sys.exit(main())
