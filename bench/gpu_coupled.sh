#!/usr/bin/env bash
# The coupled debris flow (grains in the fluid) with its lattice on a GPU: speed beside the CPU lattice in the
# same sitting, then the full-size runs to 30 s and the V_s/V_box study (bench/RESULTS.md records device,
# commands and numbers). Run from the repository root on the GPU machine:
#   bash bench/gpu_coupled.sh BUNDLE [LIMIT_S]
# BUNDLE as for bench/gpu_lattice.sh (sabo built for a portable CPU, its libraries, opencl_env.sh). LIMIT_S:
# wall seconds for the 30 s runs and the study together (default 480); everything is resumable: run the
# script again in a later sitting and the runs go on from their checkpoints. Outputs under ${SITTING_DIR:-/tmp/sabo_coupled}.
set -uo pipefail
bundle=${1:?usage: gpu_coupled.sh BUNDLE [LIMIT_S]}
limit=${2:-480}
dir=${SITTING_DIR:-/tmp/sabo_coupled}
mkdir -p "$dir"
export LD_LIBRARY_PATH="$PWD/$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# shellcheck disable=SC1091
[ -f "$bundle/opencl_env.sh" ] && . "$bundle/opencl_env.sh"
"$bundle/sabo" devices
full=(--set lattice.dt_s=2.5e-4 --set fluid.rheology=bingham --set output.report=false)
echo "== speed: the full-size coupled Bingham run (V_s/V_box 0.35) for 0.5 s, device, then the CPU's $(nproc) threads"
timeout 300 "$bundle/sabo" run cases/debris_fluid.toml "${full[@]}" --set case.end_time_s=0.5 \
  --set lattice.device=opencl --out "$dir/speed_device" --overwrite 2>&1 | grep -E "ETA|completed|rror" | tail -3
timeout 300 "$bundle/sabo" run cases/debris_fluid.toml "${full[@]}" --set case.end_time_s=0.5 \
  --threads "$(nproc)" --out "$dir/speed_cpu" --overwrite 2>&1 | grep -E "ETA|completed|rror" | tail -3
echo "== where the time went (summary.json's timing: device, then CPU)"
grep -h -A11 '"timing"' "$dir/speed_device/summary.json" "$dir/speed_cpu/summary.json" | tr -d '\n' | sed 's/"timing"/\n"timing"/g'
echo
echo "== the same 0.5 s divided between 2 ranks sharing the device (ghost planes through the host)"
if command -v mpirun > /dev/null; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 300 mpirun -np 2 "$bundle/sabo" run \
    cases/debris_fluid.toml "${full[@]}" --set case.end_time_s=0.5 --set lattice.device=opencl \
    --threads $(( $(nproc) / 2 )) --out "$dir/speed_device_2ranks" --overwrite 2>&1 | grep -E "completed|imbalance|went|rror" | tail -4
fi
start=$SECONDS
for rheology in bingham newtonian; do
  left=$((limit - (SECONDS - start)))
  [ "$left" -gt 30 ] || break
  echo "== the full-size coupled $rheology run to 30 s ($left s left)"
  out="$dir/c5_$rheology"
  resume=(--overwrite); [ -f "$out/checkpoint.bin" ] && resume=(--resume)
  timeout -k 60 "$left" "$bundle/sabo" run cases/debris_fluid.toml --set lattice.dt_s=2.5e-4 \
    --set fluid.rheology=$rheology --set lattice.device=opencl --set output.checkpoint_interval_wall_s=120 \
    --out "$out" "${resume[@]}" 2>&1 | grep -E "ETA|completed|interrupted|rror" | awk 'NR % 6 == 1 || /completed|interrupted|rror/'
done
left=$((limit - (SECONDS - start)))
if [ "$left" -gt 60 ]; then
  echo "== the V_s/V_box study to 30 s ($left s left; resumable)"
  timeout -k 60 "$left" "$bundle/sabo" sweep cases/sweeps/debris_fractions_gpu.toml --out "$dir/sweep" 2>&1 | tail -20
fi
