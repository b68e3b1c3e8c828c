#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (g++): any memory error, leak
# or undefined behaviour fails the test it happens in. About 4x slower than the normal suite.
#   bash scripts/sanitize.sh [BUILD_DIR (default build-asan)] [ctest arguments ...]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-asan}
shift || true
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSABO_SANITIZE=ON -DSABO_BUILD_BENCH=OFF >/dev/null
cmake --build "$build"
# halt on the first report; the run loop's own checks (a blow-up is a RunError) are not sanitizer findings
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir "$build" --output-on-failure "$@"
