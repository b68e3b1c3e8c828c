#!/usr/bin/env python3
"""A bed raised by a mesh carries the flow as the bed plane does.

    check_bed_mesh.py RAISED_RUN FLAT_RUN [FLAT_RUN ...]

RAISED_RUN: the channel's whole floor a meshed slab (a part named bed…) 0.2 m thick, the released block
standing on it, the barrier and the lid raised by as much: the FLAT_RUNs' flow, 0.2 m higher, on a face of
triangles instead of the bed plane. The first FLAT_RUN has the same release, the others other realisations
of it (release.perturbation_seed). The two agree to 1e-7 (of the larger value, or of 1 J, 1 N) while the
block starts to slide (to t = 0.3 s: the slab face's arithmetic differs from the plane's in the last digits,
which the contacts amplify); from then on they are realisations of one flow: the normal force on the
barrier at the end, its peak, and the bed's X force at the end — the slab's, counted as the bed's — lie
within twice the flat realisations' range of their mean. Prints "bed mesh ok: ..." or the differences,
exit 1.
"""
import sys

from check_mesh_matches_model import load  # summary.json and series.csv of a run folder


def main():
    raised, raised_rows = load(sys.argv[1])
    flats = [load(run) for run in sys.argv[2:]]
    flat, flat_rows = flats[0]
    problems = []
    compared = 0
    for rr, rf in zip(raised_rows, flat_rows):
        if float(rf["time_s"]) > 0.3:
            break
        compared += 1
        for key in rf:
            x, y = float(rr[key]), float(rf[key])
            if abs(x - y) > 1e-7 * max(abs(x), abs(y), 1.0):
                problems.append(f"row {compared} (t = {rf['time_s']} s): {key} {x} vs {y}")
                break
    if compared < 10:
        problems.append(f"only {compared} rows to t = 0.3 s")
    said = []
    for key in ("end_normal_force_N", "max_normal_force_N", "end_bed_force_x_N"):
        values = [f[key] for f, _ in flats]
        mean, spread = sum(values) / len(values), max(values) - min(values)
        if abs(raised[key] - mean) > 2.0 * spread:
            problems.append(f"{key}: {raised[key]:.6g} against the flat runs' {min(values):.6g}…{max(values):.6g}")
        said.append(f"{key} {raised[key]:.4g} (flat {min(values):.4g}…{max(values):.4g})")
    if problems:
        print("\n".join(problems[:20]))
        return 1
    print(f"bed mesh ok: {compared} rows equal to t = 0.3 s; " + ", ".join(said))
    return 0


if __name__ == "__main__":
    sys.exit(main())
