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
for rep in $(seq 1 "$reps"); do
  for win in early impact; do
    echo "# rep $rep window $win"
    ( cd "$peers" && /usr/bin/time -f "liggghts $win peak_rss_MiB=%M" bash run.sh liggghts "$win" ) 2>&1 \
      | sed -E 's/peak_rss_MiB=([0-9]+)/peak_rss_KiB=\1/'
    for t in 1 2; do "$bench" "$peers/particles.txt" "$win" --threads "$t"; done
  done
done
