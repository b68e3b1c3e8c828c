#!/usr/bin/env bash
# Every core of a workstation, and MPI ranks against threads (docs/scaling.md): the goals' runs on a
# machine of many cores (the GPU machine's 16, ../shared/device/README.md), each printing its wall time and
# its summary's `timing` block (where the time went, phase by phase). Run from the repository root:
#   bash bench/cpu_scaling.sh BUNDLE [THREADS]
# BUNDLE as for bench/gpu_lattice.sh (sabo and lbm_throughput built for a portable CPU, their libraries);
# THREADS: the cores to use (default: nproc). About 5 minutes on 16 cores. Outputs under ${SITTING_DIR:-/tmp/sabo_scaling}.
# With PERF=path/to/perf (and its libraries in PERF_LIB) a profile of the dam break and of the coupled run
# on all threads is printed too (the functions that take the time, when the machine allows perf).
set -uo pipefail
bundle=${1:?usage: cpu_scaling.sh BUNDLE [THREADS]}
n=${2:-$(nproc)}
dir=${SITTING_DIR:-/tmp/sabo_scaling}
mkdir -p "$dir"
export LD_LIBRARY_PATH="$PWD/$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
lscpu | grep -E "Model name|^CPU\(s\)|L3" ; echo "threads: $n"
timing() {  # the summary's timing block on one line
  python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['timing']; print('  timing', {k: round(v, 2) for k, v in t.items()})" "$1/summary.json" 2>/dev/null
}
run() {  # NAME LAUNCHER... -- sabo arguments: wall time and timing
  local name=$1; shift
  local start=$SECONDS
  timeout 300 "$@" --out "$dir/$name" --overwrite > "$dir/$name.log" 2>&1
  echo "$name: exit $? in $((SECONDS - start)) s; $(grep -ho 'completed: t = [^;]*' "$dir/$name.log" | tail -1)"
  timing "$dir/$name"
}
profile() {  # NAME COMMAND...: the hottest functions of COMMAND, when perf works here
  [ -n "${PERF:-}" ] || return 0
  LD_LIBRARY_PATH="${PERF_LIB:-}:$LD_LIBRARY_PATH" "$PERF" record -F 499 -o "$dir/$1.perf" -- "${@:2}" > /dev/null 2>&1 ||
    { echo "  ($1: no profile: perf record failed)"; return 0; }
  echo "  profile of $1 (self time, per function):"
  LD_LIBRARY_PATH="${PERF_LIB:-}:$LD_LIBRARY_PATH" "$PERF" report -i "$dir/$1.perf" --no-children --sort dso,symbol --stdio 2>/dev/null | sed "s/ *- *- *$//" |
    grep -E "^ +[0-9.]+%" | head -25
}
dam=(--setup dam_break --n 200 --float --bingham --steps 40)
echo "== free-surface Bingham dam break 200^3 float32: 1 thread, $((n / 2)), $n (goal: $n threads >= 10x one)"
for t in 1 $((n / 2)) "$n"; do
  OMP_NUM_THREADS=$t timeout 300 "$bundle/lbm_throughput" "${dam[@]}" | grep -iE "mlups" | head -2 | sed "s/^/  $t threads: /"
done
OMP_NUM_THREADS=$n profile dam_t$n "$bundle/lbm_throughput" "${dam[@]}"
c5=(cases/debris_fluid.toml --set lattice.dt_s=2.5e-4 --set fluid.rheology=bingham --set case.end_time_s=0.15
    --set output.report=false --set output.frame_interval_s=1)
echo "== full-size C5 coupled, 600 lattice steps: 1 thread, $((n / 2)), $n threads (goal: >= 8x), then $n ranks x 1 (goal: >= 0.8 of $n threads) and 4 ranks x $((n / 4))"
run c5_t1 "$bundle/sabo" run "${c5[@]}" --threads 1
run c5_t$((n / 2)) "$bundle/sabo" run "${c5[@]}" --threads "$((n / 2))"
run c5_t$n "$bundle/sabo" run "${c5[@]}" --threads "$n"
command -v mpirun > /dev/null && run c5_r$n mpirun -np "$n" "$bundle/sabo" run "${c5[@]}" --threads 1
command -v mpirun > /dev/null && run c5_r4 mpirun -np 4 "$bundle/sabo" run "${c5[@]}" --threads "$((n / 4))"
profile c5_t$n "$bundle/sabo" run "${c5[@]}" --threads "$n" --out "$dir/c5_profiled" --overwrite
c2=(cases/slit_barrier.toml --set channel.width_m=16.8 --set release.width_m=16.6 --set release.solid_volume_m3=32.24
    --set case.end_time_s=0.6 --set output.report=false --set output.frame_interval_s=1)
echo "== C2 widened to 61 k grains, 0.6 s: $n threads, then $n ranks x 1 (goal: >= 0.8 of the threads)"
run c2_t$n "$bundle/sabo" run "${c2[@]}" --threads "$n"
command -v mpirun > /dev/null && run c2_r$n mpirun -np "$n" "$bundle/sabo" run "${c2[@]}" --threads 1
