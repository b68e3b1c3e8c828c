#!/usr/bin/env bash
# The OpenCL lattice's throughput on a GPU machine, beside a reference bulk kernel in the same sitting
# (bench/RESULTS.md records device, commands and numbers). Run from the repository root:
#   bash bench/gpu_lattice.sh BUNDLE [N]
# BUNDLE: a folder with lbm_throughput and sabo built for a portable CPU (-march=x86-64-v3), the libraries
# they link that the machine lacks in BUNDLE/lib, and optionally the reference kernel (BUNDLE/lbm_ocl with its
# BUNDLE/cell_body.inc); BUNDLE/opencl_env.sh, if there, points the OpenCL loader at the GPU's driver.
# N: the periodic box's edge (default 256: 16.8 M cells; the barrier box is 2N/2 x N/2 x N/2).
set -uo pipefail
bundle=${1:?usage: gpu_lattice.sh BUNDLE [N]}
n=${2:-256}
export LD_LIBRARY_PATH="$PWD/$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# shellcheck disable=SC1091
[ -f "$bundle/opencl_env.sh" ] && . "$bundle/opencl_env.sh"
echo "== devices"; "$bundle/sabo" devices
steps=200
run() { echo "== lbm_throughput $*"; timeout 120 "$bundle/lbm_throughput" --device opencl --steps $steps "$@"; }
run --setup periodic --n "$n" --float
run --setup periodic --n "$n"
run --setup periodic --n "$n" --float --bingham
run --setup barrier --n $((n / 2)) --float
if [ -x "$bundle/lbm_ocl" ]; then
  echo "== reference kernel (float32 BGK, periodic, two lattices)"
  timeout 120 "$bundle/lbm_ocl" "$n" $steps "$bundle/cell_body.inc"
fi
echo "== CPU lattice, every core, same box"
OMP_NUM_THREADS=$(nproc) timeout 120 "$bundle/lbm_throughput" --setup periodic --n "$n" --steps 20 --float
