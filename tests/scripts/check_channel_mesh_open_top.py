#!/usr/bin/env python3
"""Side walls from a mesh under an open top: the fluid runs as between the box's walls until it rises over
them, then goes over them and leaves the domain's sides.

    check_channel_mesh_open_top.py BOX_RUN MESH_RUN UNTIL_S

BOX_RUN: a debris run in the box of width W (the walls the box's, an open top); MESH_RUN: the same run in a
domain two cells wider on each side between meshed slabs two cells thick standing there (the same flow
width). The lattice is the same one shifted across, so the series are equal bit for bit up to UNTIL_S (the
run-up reaching the walls' top); afterwards the fluid that rises over the walls leaves the box at once but
crosses the slabs' tops in the mesh's domain first. Asserts: the rows up to UNTIL_S equal; fluid non-retained
and over-crest fractions within 0.01; some fluid left over the sides of the mesh's domain. Prints "channel mesh open top ok: …" or the differences, exit 1.
"""
import sys

from check_mesh_matches_model import load  # (summary, series rows) of a run's folder


def main():
    (box, box_rows), (mesh, mesh_rows) = load(sys.argv[1]), load(sys.argv[2])
    until = float(sys.argv[3])
    problems = []
    equal = 0
    for a, b in zip(box_rows, mesh_rows):
        if float(a["time_s"]) > until:
            break
        if a != b:
            differing = [k for k in a if a[k] != b[k]]
            problems.append(f"t = {a['time_s']} s: {', '.join(differing[:4])} differ")
            break
        equal += 1
    if equal < 10:
        problems.append(f"only {equal} rows compared")
    for key in ("fluid_non_retained_fraction", "fluid_over_crest_fraction"):
        if abs(box[key] - mesh[key]) > 0.01:
            problems.append(f"{key}: {box[key]} (box) vs {mesh[key]} (mesh)")
    sides = mesh["fluid_left_sides_fraction"]
    if not sides > 0.0:
        problems.append("no fluid left over the mesh's walls")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"channel mesh open top ok: {equal} rows equal; non-retained {box['fluid_non_retained_fraction']:.4f} "
          f"(box) / {mesh['fluid_non_retained_fraction']:.4f} (mesh); over the sides {box['fluid_left_sides_fraction']:.4f}"
          f" / {sides:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
