#!/usr/bin/env python3
"""A run of grains divided among MPI ranks gives the results of the run on one process, statistically.

    check_divided_grains.py [--backends] ONE_RANK_DIR SEVERAL_RANKS_DIR RANKS

With --backends the two runs are one case on one process on the two lattice backends (CPU, OpenCL; RANKS 1):
the device sums the fluid in another order, so its run too is another realisation of the same flow; the
backend's own keys are then not compared.

The divided run evaluates the same contacts but adds their forces in another order, and a granular flow
amplifies round-off, so its numbers are those of another realisation of the same flow (docs/scaling.md,
"Grains in slabs"). Checked:
- exact: the grain count, the steps, the simulated time, the status, the number of series rows and of
  frames, the points of every frame (no grain lost or made), the number of ranks (RANKS);
- summary.json: every other number within 2 % of the one-process value (relative to the larger of its
  magnitude and 1 % of the peak force or of the initial kinetic energy for forces and energies), times of
  events within 0.02 s, fractions within 0.02, the fluid's mass drift (grains in a fluid) below 1e-10;
  text keys equal;
- series.csv: its first row (t = 0, before any step: the same state, only summed in another order) to 1e-9
  relative; the grains' kinetic energy at every row within 2 % of the largest plus 2 % of itself.
Prints "statistically the same results on N ranks" or the differences, exit 1.
"""
import os
import re
import sys

from check_divided_run import read_csv, read_summary  # as the fluid runs' check reads them

VOLATILE = {"wall_time_s", "timing", "threads", "particle_steps_per_s", "cell_updates_per_s", "mpi_ranks",
            "mpi_work_imbalance", "mpi_time_imbalance", "mpi_exchange_fraction", "mpi_face_moves",
            "mpi_slab_faces"}
EXACT = {"particles", "grains", "lattice_cells", "barrier_cells", "steps", "simulated_time_s", "dt_s",
         "pile_count", "neighbor_list_builds"}
PEAK_FORCE = ("max_global_force_N", "force_normal_max_N")  # a channel run's, a debris run's


def frames(run_dir):
    """The .vtp files particles.pvd lists and the number of points in each."""
    with open(os.path.join(run_dir, "particles.pvd"), encoding="utf-8") as f:
        names = re.findall(r'file="([^"]+)"', f.read())
    counts = []
    for name in names:
        with open(os.path.join(run_dir, name), "rb") as f:
            head = f.read(4096).decode("latin-1")
        counts.append(int(re.search(r'NumberOfPoints="(\d+)"', head).group(1)))
    return counts


def scale_of(key, one):
    if "force" in key or key.startswith("k_") or "moment" in key:
        peak = next((one[k] for k in PEAK_FORCE if k in one), 0.0) or 0.0
        return 0.01 * max(abs(peak), 1e-9)
    if "energy" in key:
        return 1e-9
    return 0.0


def compare(one, many, where, problems):
    for key, a in one.items():
        if key in VOLATILE:
            continue
        b = many.get(key)
        if isinstance(a, dict) or isinstance(a, list):
            if not isinstance(b, type(a)) or len(a) != len(b):
                problems.append(f"{where}{key}: {a!r} vs {b!r}")
                continue
            items = a.items() if isinstance(a, dict) else enumerate(a)
            for k, v in items:
                if isinstance(v, dict):
                    compare(v, b[k], f"{where}{key}[{k}].", problems)
            continue
        if isinstance(a, str) or isinstance(a, bool) or a is None or key in EXACT:
            if a != b:
                problems.append(f"{where}{key}: {a!r} vs {b!r}")
            continue
        if b is None:
            problems.append(f"{where}{key}: missing")
            continue
        if "relative_mass_drift" in key:  # the fluid's mass is kept on every rank count
            ok = abs(b) <= 1e-10
        elif key.endswith("_s") and ("time" in key or "t_" in key or "stop" in key):
            ok = abs(a - b) <= 0.02
        elif "fraction" in key or key.endswith("_ratio") or "over_" in key:
            ok = abs(a - b) <= 0.02 + 0.02 * abs(a)
        else:
            ok = abs(a - b) <= 0.02 * max(abs(a), abs(b)) + scale_of(key, one)
        if not ok:
            problems.append(f"{where}{key}: {a} vs {b}")


def kinetic_energy_differs(h1, rows1, rows2, problems, label=""):
    """The grains' kinetic energy of two realisations of a flow (series.csv rows of the same columns h1): at
    every row within 2 % of the first run's largest plus 2 % of itself; the first row that is not is added to
    problems."""
    k = h1.index(next(c for c in ("kinetic_energy_translational_J", "grain_kinetic_energy_J") if c in h1))
    e0 = max(r[k] for r in rows1)
    for r1, r2 in zip(rows1, rows2):
        if abs(r1[k] - r2[k]) > 0.02 * e0 + 0.02 * abs(r1[k]):
            problems.append(f"series.csv at t = {r1[0]}: kinetic energy {r1[k]} vs {r2[k]}{label}")
            return


def main():
    args = sys.argv[1:]
    backends = "--backends" in args
    if backends:
        args.remove("--backends")
        VOLATILE.update({"lattice_device", "opencl_device"})
    one_dir, many_dir, ranks = args[0], args[1], int(args[2])
    problems = []
    one, many = read_summary(one_dir), read_summary(many_dir)
    if many.get("mpi_ranks", 1) != ranks:
        problems.append(f"mpi_ranks: {many.get('mpi_ranks')} (expected {ranks})")
    compare(one, many, "", problems)
    h1, rows1 = read_csv(os.path.join(one_dir, "series.csv"))
    h2, rows2 = read_csv(os.path.join(many_dir, "series.csv"))
    if h1 != h2 or len(rows1) != len(rows2):
        problems.append(f"series.csv: {len(rows1)} rows vs {len(rows2)}, columns equal: {h1 == h2}")
    else:
        # the first row, before any step: the same state, summed over the ranks in another order
        for name, a, b in zip(h1, rows1[0], rows2[0]):
            if abs(a - b) > 1e-9 * (1.0 + abs(a)) and not (a != a and b != b):
                problems.append(f"series.csv at t = {rows1[0][0]} (before any step): {name} {a} vs {b}")
        kinetic_energy_differs(h1, rows1, rows2, problems)
    f1, f2 = frames(one_dir), frames(many_dir)
    if f1 != f2:
        problems.append(f"frames' point counts: {f1} vs {f2}")
    if problems:
        print("differences:\n  " + "\n  ".join(problems))
        return 1
    where = "on the other backend" if backends else f"on {ranks} ranks"
    print(f"statistically the same results {where} ({len(rows1)} series rows, {len(f1)} frames)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
