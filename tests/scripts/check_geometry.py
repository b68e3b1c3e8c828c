#!/usr/bin/env python3
"""A run's geometry.vtp is the surface of its channel and barrier.

    check_geometry.py RUN_DIR

Reads geometry.vtp as the VTK XML format defines it (PolyData polygons, raw appended Float64 points,
Int64 connectivity and offsets with UInt64 sizes, Float64 cell data `wall`, `barrier_sphere`, `barrier`)
and case_resolved.toml, and checks: every polygon's indices are points of the file; the bed is one polygon
of the channel (not the barrier's) lying in z = 0 and spanning the channel's length and width; both side
walls lie in y = 0 and y = W; a case with a barrier has barrier polygons, all within a sphere radius (or
0.5 m for boxes) of the barrier's place along the channel and of its height, and as many barrier spheres
as the case says (`derived.barrier_spheres`, or summary.json's `barrier_elements`); without one, none. Prints "geometry ok: …" or the problems,
exit 1.
"""
import json
import os
import re
import struct
import sys
import tomllib


def read_vtp(path):
    with open(path, "rb") as f:
        data = f.read()
    start = data.index(b"<AppendedData")
    blob = data[data.index(b"_", start) + 1:]
    head = data[:start].decode()
    arrays = {}
    for m in re.finditer(r'type="(\w+)" Name="([^"]+)" NumberOfComponents="(\d+)" format="appended" '
                         r'offset="(\d+)"', head):
        kind, name, comps, offset = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        (size,) = struct.unpack_from("<Q", blob, offset)
        code = {"Float64": "d", "Int64": "q"}[kind]
        values = struct.unpack_from(f"<{size // 8}{code}", blob, offset + 8)
        arrays[name] = [values[i:i + comps] for i in range(0, len(values), comps)] if comps > 1 else values
    polys = int(re.search(r'NumberOfPolys="(\d+)"', head).group(1))
    return polys, arrays


def main():
    run = sys.argv[1]
    problems = []
    with open(os.path.join(run, "case_resolved.toml"), "rb") as f:
        case = tomllib.load(f)
    polys, a = read_vtp(os.path.join(run, "geometry.vtp"))
    points, conn, offs = a["points"], a["connectivity"], a["offsets"]
    if len(offs) != polys or any(len(a[k]) != polys for k in ("wall", "barrier_sphere", "barrier")):
        problems.append(f"{polys} polygons, but {len(offs)} offsets and cell arrays of other lengths")
    if offs and offs[-1] != len(conn) or any(i < 0 or i >= len(points) for i in conn):
        problems.append("connectivity names points the file does not have")
    faces = [[points[i] for i in conn[(offs[p - 1] if p else 0):offs[p]]] for p in range(len(offs))]
    length, width = case["channel"]["length_m"], case["channel"]["width_m"]
    eps = 1e-9 * (length + width)

    def lies_in(face, axis, value):
        return all(abs(q[axis] - value) <= eps for q in face)

    def span(face, axis):
        return min(q[axis] for q in face), max(q[axis] for q in face)

    channel = [f for f, b in zip(faces, a["barrier"]) if b == 0]
    beds = [f for f in channel if lies_in(f, 2, 0.0)]
    if not any(abs(span(f, 0)[0]) <= eps and abs(span(f, 0)[1] - length) <= eps and abs(span(f, 1)[0]) <= eps
               and abs(span(f, 1)[1] - width) <= eps for f in beds):
        problems.append(f"no bed polygon spanning {length} x {width} m in z = 0")
    for y in (0.0, width):
        if not any(lies_in(f, 1, y) for f in channel):
            problems.append(f"no side wall in y = {y}")
    barrier = case.get("barrier", {})
    faces_of_barrier = [f for f, b in zip(faces, a["barrier"]) if b == 1]
    present = barrier.get("type", "none") != "none"
    if present:
        margin = barrier.get("sphere_radius_m", 0.5) if barrier.get("model") == "spheres" else 0.5
        with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        # (a mesh's place is the mesh's: the summary says where its face and crest came out)
        derived = case.get("derived", {})
        x0 = derived.get("barrier_face_x_m", summary.get("barrier_face_x_m", barrier.get("face_x_m")))
        height = derived.get("barrier_height_m", summary.get("barrier_height_m", barrier.get("height_m")))
        if not faces_of_barrier:
            problems.append("the barrier has no polygons")
        for f in faces_of_barrier:
            lo, hi = span(f, 0)
            zlo, zhi = span(f, 2)
            if lo < x0 - height - 2 * margin or hi > x0 + height + 2 * margin or zlo < -2 * margin or zhi > height + 2 * margin:
                problems.append(f"a barrier polygon at x {lo:.3f}–{hi:.3f}, z {zlo:.3f}–{zhi:.3f} m, away from "
                                f"the barrier at x = {x0} m, {height} m high")
                break
        spheres = len({s for s in a["barrier_sphere"] if s >= 0})
        expected = case.get("derived", {}).get("barrier_spheres")
        if expected is None:  # (the debris case: one element per sphere)
            with open(os.path.join(run, "summary.json"), encoding="utf-8") as f:
                expected = json.load(f).get("barrier_elements", 0)
        if barrier.get("type") != "mesh" and barrier.get("model") == "spheres" and spheres != expected:
            problems.append(f"{spheres} barrier spheres in the surface, the case has {expected}")
    elif faces_of_barrier:
        problems.append("barrier polygons in a case without a barrier")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"geometry ok: {polys} polygons, {len(faces_of_barrier)} of the barrier, {len(points)} points")
    return 0


if __name__ == "__main__":
    sys.exit(main())
