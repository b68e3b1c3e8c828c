#!/usr/bin/env python3
"""A run divided among MPI ranks writes what the run on one process writes.

    check_divided_run.py ONE_RANK_DIR SEVERAL_RANKS_DIR RANKS

- series.csv (and gauge.csv if there is one): every column equal but those that are sums over the ranks
  (the mass drift, the forces on the barrier, the fluid downstream of it; at the gauge everything but the
  depth), which may differ by round-off: |Δ| ≤ 1e-12 (1 + |value|), the ranks' parts being summed in
  another order; the lattice itself steps bit for bit in slabs.
- summary.json: the same values but the wall time, rates, those sums (round-off as above) and the number
  of ranks (which must be RANKS); the divided run's timing parts of its exchanges (the lattice's, the
  grains', the face moves') add up to its exchanges_s, the lattice's above zero.
- fluid.pvd names one .pvti per frame at the same times; each .pvti joins RANKS pieces (.vti) whose extents
  tile the whole image along x, and the pieces' cell arrays put side by side equal the one-process .vti's,
  value for value (read as the VTK XML format defines them: raw appended Float32 blocks with UInt64 sizes).
Prints "same results on N ranks" or the differences, exit 1.
"""
import json
import os
import re
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

VOLATILE = {"wall_time_s", "timing", "threads", "cell_updates_per_s", "mlups", "mpi_ranks", "mpi_work_imbalance",
            "mpi_time_imbalance", "mpi_exchange_fraction", "mpi_face_moves", "mpi_slab_faces"}


def summed(name, gauge=False):
    """Whether a column or key is a sum over the ranks' parts (equal to round-off only)."""
    if gauge:
        return name not in ("time_s", "depth_m")
    return ("drift" in name or "force" in name or "non_retained" in name or name.startswith("approach_")
            or name.startswith("k_") or "impact" in name or name.startswith("fluid_over_crest")
            or name.startswith("fluid_through_outlets") or name.startswith("fluid_spread_behind"))


def close(x, y):
    return x == y or abs(x - y) <= 1e-12 * (1.0 + abs(x))


def read_summary(run_dir):
    with open(os.path.join(run_dir, "summary.json"), encoding="utf-8") as f:
        return json.load(f)


def read_csv(path):
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip().split(",")
        return header, [[float(v) for v in line.split(",")] for line in f if line.strip()]


def appended_bytes(blob, offset, compressed):
    """One array's bytes in raw appended data (UInt64 headers): a size and the bytes, or, with VTK's zlib
    compressor, [blocks, block size, last partial block's size, each block's compressed size] and the blocks."""
    if not compressed:
        (size,) = struct.unpack_from("<Q", blob, offset)
        return blob[offset + 8:offset + 8 + size]
    blocks, _, _ = struct.unpack_from("<3Q", blob, offset)
    sizes = struct.unpack_from(f"<{blocks}Q", blob, offset + 24)
    at = offset + 24 + 8 * blocks
    out = b""
    for size in sizes:
        out += zlib.decompress(blob[at:at + size])
        at += size
    return out


def read_vti(path):
    """(extent, {name: (components, values)}) of an ImageData file with raw appended data."""
    with open(path, "rb") as f:
        data = f.read()
    start = data.index(b"<AppendedData")
    blob = data[data.index(b"_", start) + 1:]
    head = data[:start].decode()
    compressed = "vtkZLibDataCompressor" in head
    extent = [int(v) for v in re.search(r'<Piece Extent="([^"]+)"', head).group(1).split()]
    arrays = {}
    for m in re.finditer(r'Name="([^"]+)" NumberOfComponents="(\d+)" format="appended" offset="(\d+)"', head):
        raw = appended_bytes(blob, int(m.group(3)), compressed)
        arrays[m.group(1)] = (int(m.group(2)), struct.unpack(f"<{len(raw) // 4}f", raw))
    return extent, arrays


def frames(run_dir):
    root = ET.parse(os.path.join(run_dir, "fluid.pvd")).getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def joined(pvti_path, ranks, problems):
    """The pieces of a .pvti put side by side along x: {name: values in x-fastest order}."""
    root = ET.parse(pvti_path).getroot()
    image = root.find("PImageData")
    whole = [int(v) for v in image.get("WholeExtent").split()]
    pieces = image.findall("Piece")
    if len(pieces) != ranks:
        problems.append(f"{pvti_path}: {len(pieces)} pieces, expected {ranks}")
    nx, ny, nz = whole[1] - whole[0], whole[3] - whole[2], whole[5] - whole[4]
    out, covered = {}, []
    for piece in pieces:
        extent, arrays = read_vti(os.path.join(os.path.dirname(pvti_path), piece.get("Source")))
        if [int(v) for v in piece.get("Extent").split()] != extent:
            problems.append(f"{piece.get('Source')}: extent differs from the .pvti's")
        x0, x1 = extent[0], extent[1]
        covered.append((x0, x1))
        for name, (comps, values) in arrays.items():
            whole_values = out.setdefault(name, [None] * (nx * ny * nz * comps))
            w = x1 - x0
            for z in range(nz):
                for y in range(ny):
                    src = ((z * ny + y) * w) * comps
                    dst = ((z * ny + y) * nx + x0) * comps
                    whole_values[dst:dst + w * comps] = values[src:src + w * comps]
    covered.sort()
    if covered[0][0] != 0 or covered[-1][1] != nx or any(a[1] != b[0] for a, b in zip(covered, covered[1:])):
        problems.append(f"{pvti_path}: the pieces {covered} do not tile 0..{nx}")
    return out


def main():
    one, several, ranks = sys.argv[1], sys.argv[2], int(sys.argv[3])
    problems = []
    for csv_name in ("series.csv", "gauge.csv"):
        if csv_name == "gauge.csv" and not os.path.exists(os.path.join(one, csv_name)):
            continue
        ha, ra = read_csv(os.path.join(one, csv_name))
        hb, rb = read_csv(os.path.join(several, csv_name))
        if ha != hb or len(ra) != len(rb):
            problems.append(f"{csv_name}: {len(ra)} rows of {ha} vs {len(rb)} of {hb}")
            continue
        for i, (a, b) in enumerate(zip(ra, rb)):
            for name, x, y in zip(ha, a, b):
                if x != y and not (summed(name, csv_name == "gauge.csv") and close(x, y)):
                    problems.append(f"{csv_name} row {i} {name}: {x} vs {y}")
    sa, sb = read_summary(one), read_summary(several)
    if sb.get("mpi_ranks") != ranks:
        problems.append(f"summary.json mpi_ranks: {sb.get('mpi_ranks')}, expected {ranks}")
    # the divided run's exchanges, part by part: they add up to the whole (to summary.json's 9 significant
    # digits: each of the four values rounded by at most 5e-9 of the whole, which no part exceeds)
    t = sb.get("timing", {})
    parts = [t.get(k, -1.0) for k in ("exchanges_lattice_s", "exchanges_grains_s", "exchanges_face_moves_s")]
    whole = t.get("exchanges_s", -1.0)
    if (min(parts) < 0.0 or not t.get("exchanges_lattice_s", 0.0) > 0.0
            or abs(sum(parts) - whole) > 2e-8 * max(abs(whole), 1e-300)):
        problems.append(f"summary.json timing's exchanges: {t}")
    # the free surface's passes are a part of the lattice's steps, neither holding the waits for the others
    if not 0.0 <= t.get("lattice_free_surface_s", -1.0) <= t.get("lattice_s", -1.0):
        problems.append(f"summary.json timing's free surface beyond the lattice's steps: {t}")
    for key in sorted(set(sa) | set(sb)):
        if key in VOLATILE or key.endswith("_per_s") or sa.get(key) == sb.get(key):
            continue
        if summed(key) and isinstance(sa.get(key), float) and isinstance(sb.get(key), float) and close(sa[key], sb[key]):
            continue
        problems.append(f"summary.json {key}: {sa.get(key)} vs {sb.get(key)}")
    fa, fb = frames(one), frames(several)
    if [t for t, _ in fa] != [t for t, _ in fb]:
        problems.append(f"fluid.pvd: frame times differ ({len(fa)} vs {len(fb)} frames)")
    for (_, file_a), (_, file_b) in zip(fa, fb):
        if not file_b.endswith(".pvti"):
            problems.append(f"fluid.pvd names {file_b}, not a .pvti")
            continue
        _, arrays = read_vti(os.path.join(one, file_a))
        pieces = joined(os.path.join(several, file_b), ranks, problems)
        for name, (_, values) in arrays.items():
            if list(values) != pieces.get(name):
                problems.append(f"{file_b} {name}: differs from {file_a}")
    for p in problems[:20]:
        print(p)
    print(f"same results on {ranks} ranks" if not problems else f"{len(problems)} differences")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
