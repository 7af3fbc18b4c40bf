#!/usr/bin/env bash
# Sanitizer stage: builds everything in build-asan/ with AddressSanitizer (+LeakSanitizer) and
# UndefinedBehaviorSanitizer (-O1 -g, every report fatal) and runs the whole ctest suite.
# Fails on any sanitizer report. Usage: scripts/test-sanitizers.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
src=$PWD
build=${1:-build-asan}
jobs=$(nproc)
werror=OFF
[ -n "${CI:-}" ] && werror=ON

t0=$(date +%s)
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DRADARSLAM_SANITIZE=address,undefined -DRADARSLAM_BUILD_BENCHMARKS=OFF \
  -DRADARSLAM_WERROR=$werror >/dev/null
cmake --build "$build" -j"$jobs"
t1=$(date +%s)

# detect_leaks: LSan at exit; abort_on_error: a report kills the test (ctest sees a failure).
# Suppressions are narrowly scoped third-party entries, each with a reason (test/sanitizers/).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$src/test/sanitizers/lsan.supp:print_suppressions=0"
cd "$build"
ctest -j"$jobs" --output-on-failure --timeout 1800
t2=$(date +%s)
echo "sanitizer stage: build $((t1 - t0)) s, tests $((t2 - t1)) s on $jobs cores"
