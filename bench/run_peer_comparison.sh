#!/usr/bin/env bash
# Side-by-side DEM throughput: LIGGGHTS (Debian package, via ../shared/peers/dem/run.sh) and Sabo
# on the same 7640-grain packing, both windows, alternating the programs in one sitting.
#   bash bench/run_peer_comparison.sh [REPEATS] [BUILD_DIR]     (default 3, build)
# Needs: apt-get install -y liggghts time. Writes one line per run to stdout (and peak RSS).
set -euo pipefail
reps=${1:-3}
build=${2:-build}
here=$(cd "$(dirname "$0")/.." && pwd)
peers="$here/../shared/peers/dem"
bench="$here/$build/bench/dem_throughput"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for rep in $(seq 1 "$reps"); do
  for win in early impact; do
    echo "# rep $rep window $win"
    ( cd "$peers" && /usr/bin/time -f "liggghts $win peak_rss_MiB=%M" bash run.sh liggghts "$win" ) 2>&1 \
      | sed -E 's/peak_rss_MiB=([0-9]+)/peak_rss_KiB=\1/'
    for t in 1 2; do "$bench" "$peers/particles.txt" "$win" --threads "$t"; done
  done
done 2>&1 | tee "$log"
# Summary. The machine drifts by 10-30 % between runs, so two estimates are given per window: the
# median over repeats of the in-repeat ratio, and the ratio of each program's best run (the least
# disturbed one).
awk '
  function rate(line) { match(line, /particle_steps_per_s=[0-9.e+]+/); return substr(line, RSTART + 21, RLENGTH - 21) + 0 }
  /^# rep/ { rep = $3 }
  /^liggghts (early|impact) steps=/ { w = $2; l[w, rep] = rate($0); if (rate($0) > bl[w]) bl[w] = rate($0) }
  /^sabo (early|impact) threads=1 / { w = $2; s1[w, rep] = rate($0); if (rate($0) > b1[w]) b1[w] = rate($0) }
  /^sabo (early|impact) threads=2 / { w = $2; s2[w, rep] = rate($0); if (rate($0) > b2[w]) b2[w] = rate($0) }
  END {
    for (wi = 1; wi <= 2; ++wi) {
      w = wi == 1 ? "early" : "impact"; n = 0
      for (r = 1; r <= rep; ++r) if (l[w, r] > 0 && s1[w, r] > 0) { ++n; pc[n] = s1[w, r] / l[w, r]; sp[n] = s2[w, r] / s1[w, r] }
      for (i = 2; i <= n; ++i) for (j = i; j > 1 && pc[j] < pc[j - 1]; --j) { t = pc[j]; pc[j] = pc[j - 1]; pc[j - 1] = t }
      for (i = 2; i <= n; ++i) for (j = i; j > 1 && sp[j] < sp[j - 1]; --j) { t = sp[j]; sp[j] = sp[j - 1]; sp[j - 1] = t }
      printf "SUMMARY %s: per core (median of repeats) %.2f, speed-up 1->2 threads (median) %.2f; best runs: LIGGGHTS %.3g, Sabo 1 thread %.3g (x%.2f), 2 threads %.3g (x%.2f of 1 thread)\n", w, pc[int((n + 1) / 2)], sp[int((n + 1) / 2)], bl[w], b1[w], b1[w] / bl[w], b2[w], b2[w] / b1[w]
    }
  }' "$log"
