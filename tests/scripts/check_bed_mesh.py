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

from check_mesh_matches_model import load, rows_agree, within_realisations


def main():
    raised, raised_rows = load(sys.argv[1])
    flats = [load(run) for run in sys.argv[2:]]
    flat, flat_rows = flats[0]
    compared, problems = rows_agree(raised_rows, flat_rows, lambda r: float(r["time_s"]) > 0.3, "to t = 0.3 s")
    if compared < 10:
        problems.append(f"only {compared} rows to t = 0.3 s")
    differ, said = within_realisations(
        raised, flats, ("end_normal_force_N", "max_normal_force_N", "end_bed_force_x_N"), "flat")
    problems += differ
    if problems:
        print("\n".join(problems[:20]))
        return 1
    print(f"bed mesh ok: {compared} rows equal to t = 0.3 s; " + ", ".join(said))
    return 0


if __name__ == "__main__":
    sys.exit(main())
