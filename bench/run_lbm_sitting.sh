#!/usr/bin/env bash
# One lattice Boltzmann sitting (issue 5 item 6): the triad bandwidth at 1 and 2 threads, then the bulk
# kernel (periodic N³ box) and the free-surface dam break (N³ box) for float32/float64 x Newtonian/Bingham
# at 1 and 2 threads, REPEATS rounds, each printed next to its roofline (the best 2-thread triad with
# write-allocate of the sitting / bytes per update).
#   bash bench/run_lbm_sitting.sh [REPEATS] [BUILD_DIR] [N]     (default 2, build, 200)
# Run it on an otherwise idle machine: the bandwidth is shared, so anything else running moves the numbers.
set -euo pipefail
reps=${1:-2}
build=${2:-build}
n=${3:-200}
bench="$build/bench"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for t in 1 2; do
  for rep in $(seq 1 "$reps"); do
    OMP_NUM_THREADS=$t "$bench/memory_bandwidth" --mib 512 | tee -a "$log"
  done
done
bw=$(awk '/^RESULT triad threads=2/ { match($0, /GB_s_with_write_allocate=[0-9.]+/); v = substr($0, RSTART + 25, RLENGTH - 25) + 0; if (v > b) b = v } END { print b }' "$log")
echo "# roofline bandwidth (best 2-thread triad with write-allocate): $bw GB/s"
for rep in $(seq 1 "$reps"); do
  for setup in periodic dam_break; do
    for kind in "" "--float" "--bingham" "--float --bingham"; do
      for t in 1 2; do
        # shellcheck disable=SC2086
        OMP_NUM_THREADS=$t "$bench/lbm_throughput" --setup "$setup" --n "$n" --steps 30 --bandwidth "$bw" $kind |
          tee -a "$log"
      done
    done
  done
done
# Summary: median over the rounds of each set-up, storage, rheology and thread count.
awk '
  /^RESULT lbm/ {
    key = ""; for (i = 3; i <= 5; ++i) key = key " " $i
    match($0, /threads=[0-9]+/); key = key " " substr($0, RSTART, RLENGTH)
    match($0, / MLUPS=[0-9.]+/); v = substr($0, RSTART + 7, RLENGTH - 7) + 0
    match($0, /fraction_of_roofline=[0-9.]+/); fr = substr($0, RSTART + 21, RLENGTH - 21) + 0
    c = ++cnt[key]; val[key, c] = v; frac[key, c] = fr; if (!(key in seen)) { seen[key] = 1; order[++nk] = key }
  }
  END {
    for (k = 1; k <= nk; ++k) {
      key = order[k]; c = cnt[key]
      for (i = 2; i <= c; ++i) for (j = i; j > 1 && val[key, j] < val[key, j - 1]; --j) {
        t = val[key, j]; val[key, j] = val[key, j - 1]; val[key, j - 1] = t
        t = frac[key, j]; frac[key, j] = frac[key, j - 1]; frac[key, j - 1] = t }
      lo = int((c + 1) / 2); hi = int(c / 2) + 1  # the middle one, or the two middle ones
      printf "SUMMARY%s: MLUPS median %.1f (min %.1f, max %.1f), fraction of roofline %.2f\n", key, (val[key, lo] + val[key, hi]) / 2, val[key, 1], val[key, c], (frac[key, lo] + frac[key, hi]) / 2
    }
  }' "$log"
