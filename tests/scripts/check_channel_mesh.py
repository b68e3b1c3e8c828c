#!/usr/bin/env python3
"""Side walls from a mesh act as the channel's plane side walls.

    check_channel_mesh.py MESH_RUN BOX_RUN [BOX_RUN ...]

MESH_RUN: the channel's side walls as two meshed slabs just outside the channel's width; the BOX_RUNs: the
plane walls, the first with the same release, the others other realisations of it (release.perturbation_seed). A sphere touches a
meshed slab's face as it touches a plane (tests/dem/mesh_wall_test.cpp): the mesh run follows the first box
run, its rows equal to 1e-7 of the larger value (or of 1 J, 1 N: the slab face's arithmetic differs from the
plane's in the last digits, and the collisions amplify that) until the first impact on the barrier, which happens at the same time to 1e-9; from then on the two are
realisations of one flow: its normal force at the end and the side walls' X force at the end lie within twice the
box realisations' range of their mean, its peak within twice that range too (a peak is one collision).
Prints "channel mesh ok: ..." or the differences, exit 1.
"""
import sys

from check_mesh_matches_model import load  # summary.json and series.csv of a run folder


def main():
    mesh, mesh_rows = load(sys.argv[1])
    boxes = [load(run) for run in sys.argv[2:]]
    box, box_rows = boxes[0]
    problems = []
    before = 0
    for rm, rb in zip(mesh_rows, box_rows):
        if float(rb["barrier_force_resultant_N"]) != 0.0:
            break
        before += 1
        for key in rb:
            x, y = float(rm[key]), float(rb[key])
            if abs(x - y) > 1e-7 * max(abs(x), abs(y), 1.0):
                problems.append(f"before the impact, row {before}: {key} {x} vs {y}")
                break
    if before < 20:
        problems.append(f"only {before} rows before the impact")
    if abs(mesh["first_impact_time_s"] - box["first_impact_time_s"]) > 1e-9:
        problems.append(f"first impact {mesh['first_impact_time_s']} vs {box['first_impact_time_s']}")
    said = []
    for key in ("end_normal_force_N", "end_side_walls_force_x_N", "max_normal_force_N"):
        values = [b[key] for b, _ in boxes]
        mean, spread = sum(values) / len(values), max(values) - min(values)
        if abs(mesh[key] - mean) > 2.0 * spread:
            problems.append(f"{key}: {mesh[key]:.6g} against the box runs' {min(values):.6g}…{max(values):.6g}")
        said.append(f"{key} {mesh[key]:.4g} (box {min(values):.4g}…{max(values):.4g})")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"channel mesh ok: {before} rows equal before the impact; " + ", ".join(said))
    return 0


if __name__ == "__main__":
    sys.exit(main())
