#!/usr/bin/env bash
# One lattice Boltzmann sitting (issue 5 item 6): the triad bandwidth at 1 and 2 threads, then the bulk
# kernel (periodic N³ box) and the free-surface dam break (N³ box) for float32/float64 x Newtonian/Bingham
# at 1 and 2 threads, REPEATS rounds, each printed next to its roofline. The roofline is paired: every
# pair of steps runs between two triad passes (lbm_throughput --paired-triad), and the fraction is the
# median of the pairs' own (traffic rate / the bandwidth of that moment), because a shared machine's
# bandwidth changes within seconds (seen here: 61 and 107 GB/s, switching back and forth). The separate
# triads at the start are printed for reference.
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
for rep in $(seq 1 "$reps"); do
  for setup in periodic dam_break; do
    for kind in "" "--float" "--bingham" "--float --bingham"; do
      for t in 1 2; do
        # shellcheck disable=SC2086
        OMP_NUM_THREADS=$t "$bench/lbm_throughput" --setup "$setup" --n "$n" --steps 30 --paired-triad 256 $kind |
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
    match($0, /paired_triad_GB_s=[0-9.]+/); bw = substr($0, RSTART + 18, RLENGTH - 18) + 0
    c = ++cnt[key]; val[key, c] = v; frac[key, c] = fr
    if (c == 1 || bw < tmin[key]) tmin[key] = bw; if (c == 1 || bw > tmax[key]) tmax[key] = bw
    if (!(key in seen)) { seen[key] = 1; order[++nk] = key }
  }
  END {
    for (k = 1; k <= nk; ++k) {
      key = order[k]; c = cnt[key]
      lo = int((c + 1) / 2); hi = int(c / 2) + 1  # the middle one, or the two middle ones
      # each column sorted on its own: the median MLUPS, and the median fraction of the paired roofline
      for (i = 2; i <= c; ++i) for (j = i; j > 1 && val[key, j] < val[key, j - 1]; --j) {
        t = val[key, j]; val[key, j] = val[key, j - 1]; val[key, j - 1] = t }
      for (i = 2; i <= c; ++i) for (j = i; j > 1 && frac[key, j] < frac[key, j - 1]; --j) {
        t = frac[key, j]; frac[key, j] = frac[key, j - 1]; frac[key, j - 1] = t }
      printf "SUMMARY%s: MLUPS median %.1f (min %.1f, max %.1f), fraction of the paired roofline median %.2f (min %.2f, max %.2f; paired triads %.1f-%.1f GB/s)\n", key, (val[key, lo] + val[key, hi]) / 2, val[key, 1], val[key, c], (frac[key, lo] + frac[key, hi]) / 2, frac[key, 1], frac[key, c], tmin[key], tmax[key]
    }
  }' "$log"
