#!/usr/bin/env bash
# Fuzzes the case-file parser and the checkpoint reader with libFuzzer (clang), the library built with the
# address and undefined-behaviour sanitizers (docs/restart.md, "Hostile input"). Exits non-zero on any
# finding (crash, sanitizer report, hang > 10 s, > 2 GB, an exception other than a refusal); the input
# that caused it is left in the build folder (crash-*, timeout-*, oom-*) and can be replayed with
# `build-fuzz/fuzz/<target> <file>`.
#   bash scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [BUILD_DIR (default build-fuzz)]
# SABO_FUZZ_SEED: libFuzzer's random seed (default 1: the test suite's run is reproducible; 0: from the clock).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
build=${2:-build-fuzz}
cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSABO_FUZZ=ON -DSABO_BUILD_TESTS=OFF -DSABO_BUILD_BENCH=OFF -DSABO_NATIVE=OFF >/dev/null
cmake --build "$build" --target case_parser_fuzz checkpoint_fuzz
corpus="$build/corpus"
rm -rf "$corpus" && mkdir -p "$corpus/case" "$corpus/checkpoint"
cp cases/*.toml tests/bad_cases/*.toml "$corpus/case/"
export SABO_FUZZ_WRITE_SEEDS="$corpus/checkpoint"  # real checkpoints of tiny runs as the seeds
cd "$build"
for target in case_parser_fuzz checkpoint_fuzz; do
  dir=corpus/checkpoint
  [ "$target" = case_parser_fuzz ] && dir=corpus/case
  echo "fuzzing $target for $seconds s (corpus $build/$dir)"
  rc=0
  ./fuzz/$target -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -seed="${SABO_FUZZ_SEED:-1}" "$dir" \
    >"$target.log" 2>&1 || rc=$?
  grep -E "^(Done|==[0-9]+==|SUMMARY)|runtime error|terminate|what\(\)" "$target.log" || true
  if [ "$rc" -ne 0 ]; then
    echo "$target: a finding (exit $rc; $build/$target.log, the input in $build/crash-*|timeout-*|oom-*)" >&2
    exit 1
  fi
done
echo "fuzzing: no finding"
