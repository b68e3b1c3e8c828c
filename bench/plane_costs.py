#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Per-plane contents of a debris run's frames, for the slab-balance model (docs/scaling.md).

    python3 bench/plane_costs.py RUN_DIR > planes.csv

For each frame of RUN_DIR/frames (fluid_NNNNN.vti with its cell types, particles_NNNNN.vtp): per lattice
plane along X, the counts of fluid, interface, gas and obstacle cells and of grain centres. Columns:
frame,time_s,plane,fluid,interface,gas,obstacle,grains. Needs Debian's python3-numpy.
"""
import glob
import os
import re
import sys

import numpy as np


def appended(path):
    """The raw appended arrays of a VTK XML file written by Sabo: {name: (type, components, bytes)}."""
    with open(path, "rb") as f:
        data = f.read()
    head, _, tail = data.partition(b"<AppendedData encoding=\"raw\">")
    start = tail.index(b"_") + 1
    arrays = {}
    for m in re.finditer(rb'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" format="appended" '
                         rb'offset="(\d+)"', head):
        kind, name, comps, off = m.group(1).decode(), m.group(2).decode(), int(m.group(3)), int(m.group(4))
        size = int(np.frombuffer(tail, np.uint64, 1, start + off)[0])
        dtype = {"Float32": np.float32, "Float64": np.float64, "Int64": np.int64}[kind]
        arrays[name] = np.frombuffer(tail, dtype, size // np.dtype(dtype).itemsize, start + off + 8)
    return head.decode(errors="replace"), arrays


def main():
    run = sys.argv[1]
    times = [float(t) for t in re.findall(r'timestep="([^"]+)"', open(os.path.join(run, "fluid.pvd")).read())]
    print("frame,time_s,plane,fluid,interface,gas,obstacle,grains")
    for k, path in enumerate(sorted(glob.glob(os.path.join(run, "frames", "fluid_*.vti")))):
        head, arrays = appended(path)
        ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
        origin = [float(v) for v in re.search(r'Origin="([^"]+)"', head).group(1).split()]
        dx = float(re.search(r'Spacing="([^"]+)"', head).group(1).split()[0])
        nx, ny, nz = ext[1] - ext[0], ext[3] - ext[2], ext[5] - ext[4]
        types = arrays["cell_type"].reshape(nz, ny, nx)
        counts = [np.count_nonzero(types == t, axis=(0, 1)) for t in range(4)]
        grains = np.zeros(nx, dtype=int)
        particles = path.replace("fluid_", "particles_").replace(".vti", ".vtp")
        if os.path.exists(particles):
            x = appended(particles)[1]["points"].reshape(-1, 3)[:, 0]
            planes = np.clip(((x - origin[0]) / dx).astype(int), 0, nx - 1)
            grains = np.bincount(planes, minlength=nx)
        t = times[k] if k < len(times) else float("nan")
        for p in range(nx):
            print(f"{k},{t:.4g},{p},{counts[0][p]},{counts[1][p]},{counts[2][p]},{counts[3][p]},{grains[p]}")


if __name__ == "__main__":
    main()
