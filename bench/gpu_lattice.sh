#!/usr/bin/env bash
# The OpenCL lattice's throughput on a GPU machine, beside a reference bulk kernel in the same sitting
# (bench/RESULTS.md records device, commands and numbers). Run from the repository root:
#   bash bench/gpu_lattice.sh BUNDLE [N] [C5_SECONDS]
# BUNDLE: a folder with lbm_throughput and sabo built for a portable CPU (-march=x86-64-v3), the libraries
# they link that the machine lacks in BUNDLE/lib, and optionally the reference kernel (BUNDLE/lbm_ocl with its
# BUNDLE/cell_body.inc); BUNDLE/opencl_env.sh, if there, points the OpenCL loader at the GPU's driver.
# N: the periodic box's edge (default 256: 16.8 M cells; the barrier box is 2N/2 x N/2 x N/2).
# C5_SECONDS: wall seconds allowed to the full-size debris fluid alone to 30 s (default 400; stopped there,
# its progress lines give the rate). Runs write into ${SITTING_DIR:-/tmp/sabo_sitting}.
set -uo pipefail
bundle=${1:?usage: gpu_lattice.sh BUNDLE [N] [C5_SECONDS]}
n=${2:-256}
c5_seconds=${3:-400}
dir=${SITTING_DIR:-/tmp/sabo_sitting}
mkdir -p "$dir"
export LD_LIBRARY_PATH="$PWD/$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# shellcheck disable=SC1091
[ -f "$bundle/opencl_env.sh" ] && . "$bundle/opencl_env.sh"
echo "== devices"; "$bundle/sabo" devices
steps=200
run() { echo "== lbm_throughput $*"; timeout 120 "$bundle/lbm_throughput" --device opencl "$@"; }
run --setup periodic --n "$n" --steps $steps --float --profile
if [ -x "$bundle/lbm_ocl" ]; then
  echo "== reference kernel (float32 BGK, periodic, two lattices)"
  timeout 120 "$bundle/lbm_ocl" "$n" $steps "$bundle/cell_body.inc"
fi
run --setup dam_break --n 200 --steps $steps --float --bingham --profile
echo "== the full-size debris fluid alone to 30 s (open channel, dt 2.5e-4 s: 120 000 steps of 10.9 M cells)"
start=$SECONDS
timeout -k 60 "$c5_seconds" "$bundle/sabo" run cases/debris_fluid.toml --set debris.solid_fraction=0 \
  --set lattice.dt_s=2.5e-4 --set lattice.device=opencl --out "$dir/c5_fluid" --overwrite 2>&1 |
  grep -v "^\[.*\] \[warning\]" | awk 'NR <= 20 || /ETA|finished|wall|peak|error/'
echo "c5 exit ${PIPESTATUS[0]} after $((SECONDS - start)) s"
[ -f "$dir/c5_fluid/summary.json" ] && grep -E '"(wall|peak|fluid_)' "$dir/c5_fluid/summary.json" | head -20
echo "== the same, 40 s with a row every 1 s and a frame every 10 s (what the rows and frames cost)"
timeout -k 60 40 "$bundle/sabo" run cases/debris_fluid.toml --set debris.solid_fraction=0 \
  --set lattice.dt_s=2.5e-4 --set lattice.device=opencl --set output.series_interval_s=1 \
  --set output.frame_interval_s=10 --out "$dir/c5_sparse" --overwrite 2>&1 | grep ETA | tail -3
run --setup periodic --n "$n" --steps $steps
run --setup periodic --n "$n" --steps $steps --float --bingham
run --setup barrier --n $((n / 2)) --steps $steps --float
run --setup dam_break --n 400 --steps $steps --float --bingham --profile
echo "== CPU lattice, every core, same boxes"
OMP_NUM_THREADS=$(nproc) timeout 120 "$bundle/lbm_throughput" --setup periodic --n "$n" --steps 20 --float
OMP_NUM_THREADS=$(nproc) timeout 120 "$bundle/lbm_throughput" --setup dam_break --n 200 --steps 20 --float --bingham
