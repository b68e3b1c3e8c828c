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

from check_mesh_matches_model import load, rows_agree, within_realisations


def main():
    mesh, mesh_rows = load(sys.argv[1])
    boxes = [load(run) for run in sys.argv[2:]]
    box, box_rows = boxes[0]
    before, problems = rows_agree(mesh_rows, box_rows, lambda r: float(r["barrier_force_resultant_N"]) != 0.0,
                                  "before the impact")
    if before < 20:
        problems.append(f"only {before} rows before the impact")
    if abs(mesh["first_impact_time_s"] - box["first_impact_time_s"]) > 1e-9:
        problems.append(f"first impact {mesh['first_impact_time_s']} vs {box['first_impact_time_s']}")
    differ, said = within_realisations(
        mesh, boxes, ("end_normal_force_N", "end_side_walls_force_x_N", "max_normal_force_N"), "box")
    problems += differ
    if problems:
        print("\n".join(problems))
        return 1
    print(f"channel mesh ok: {before} rows equal before the impact; " + ", ".join(said))
    return 0


if __name__ == "__main__":
    sys.exit(main())
