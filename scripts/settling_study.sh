#!/bin/bash
# SPDX-License-Identifier: MIT
# The settling sphere at three resolutions (d/dx = 6, 8, 10) and four viscosities (Reynolds numbers at the
# terminal velocity of about 0.7, 7, 20 and 36): cases/settling_sphere.toml in a 6 d x 6 d x 18 d box, the
# sphere released 2 d below the lid; tau kept per viscosity (dt = 1e-4 s (8 / (d/dx))^2: tau 0.642, 0.538,
# 0.519, 0.512; the hydrostatic compression of the column stays under 6 %). Writes one run folder per
# point under OUT and OUT/study.csv (python/settling_study.py). MODEL: coupling.model, cell_centre (default) or
# psm (partially saturated cells). Usage: scripts/settling_study.sh OUT [SABO] [MODEL]
set -euo pipefail
out=${1:?usage: settling_study.sh OUT [SABO] [MODEL]}
sabo=${2:-build/sabo}
model=${3:-cell_centre}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
printf 'x_m,y_m,z_m,radius_m\n0.0301,0.0302,0.1600,0.005\n' > "$out/grain.csv"
for eta in 0.74 0.2 0.1 0.065; do
  case $eta in 0.74) end=0.4 ;; *) end=0.35 ;; esac
  for n in 6 8 10; do
    dx=$(python3 -c "print(0.01 / $n)")
    dt=$(python3 -c "print(1.0e-4 * (8 / $n) ** 2)")
    run="$out/eta${eta}_n${n}"
    [ -f "$run/summary.json" ] && continue
    "$sabo" run "$here/cases/settling_sphere.toml" --out "$run" --overwrite --set grains.file="$out/grain.csv" \
      --set box.height_m=0.18 --set fluid.viscosity_Pa_s=$eta --set lattice.dx_m=$dx --set lattice.dt_s=$dt \
      --set case.end_time_s=$end --set output.frame_interval_s=$end --set output.report=false \
      --set coupling.model=$model > "$run.log" 2>&1
    tail -1 "$run.log" | cut -c1-200
  done
done
python3 "$here/python/settling_study.py" "$out"
