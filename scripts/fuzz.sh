#!/usr/bin/env bash
# Bounded libFuzzer run of every parser of outside data (docs/hardening.md).
# Usage: scripts/fuzz.sh [seconds-per-target] [build-dir]      (default 30 s, build-fuzz/)
# Builds the fuzzers with clang-14 (ASan + UBSan + libFuzzer), seeds each from the committed
# synthetic corpus test/fuzz/seeds/<target>/ plus, when present, real files from
# ../shared/data/real (copied to a temp corpus, never committed), runs each target for the given
# time and fails on any crash, sanitizer report, uncaught non-InputError exception, hang (> 10 s
# per input) or out-of-memory. Prints executions per target and in total. Crash inputs are
# kept in <build-dir>/fuzz-artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$PWD
seconds=${1:-30}
build=${2:-build-fuzz}
real=$src/../shared/data/real

if [ ! -f "$build/build.ninja" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DRADARSLAM_BUILD_FUZZERS=ON -DRADARSLAM_BUILD_BENCHMARKS=OFF -DRADARSLAM_WERROR=OFF >/dev/null
fi
cmake --build "$build" -j"$(nproc)" --target fuzzers

work=$(mktemp -d /tmp/radarslam-fuzz.XXXXXX)
trap 'rm -rf "$work"' EXIT
artifacts=$src/$build/fuzz-artifacts
mkdir -p "$artifacts"

# Real seed files per target: small ones only (libFuzzer truncates inputs to -max_len anyway).
real_seeds() {
  local target=$1
  [ -d "$real" ] || return 0
  case $target in
    polar_png_oxford) find "$real"/oxford_radar_robotcar_tiny/radar -name '*.png' | head -2 ;;
    polar_png_transposed) find "$real"/radiate_tiny_foggy/Navtech_Polar -name '*.png' | head -2 ;;
    mulran_ray_csv) find "$real"/mulran_single_ray_scan -name '*.csv' ;;
    gt_oxford) echo "$real"/oxford_radar_robotcar_tiny/gt/radar_odometry.csv ;;
    gt_boreas) find "$real"/boreas_gt_only -name radar_poses.csv ;;
    radiate_frame_times) echo "$real"/radiate_tiny_foggy/Navtech_Polar.txt ;;
    oxford_timestamps) echo "$real"/oxford_radar_robotcar_tiny/radar.timestamps ;;
  esac
}

# Inputs up to 64 KiB: enough for a few-row polar PNG or a CSV head, keeps each run fast.
max_len=65536

# One target: its corpus, its run, its exit code in $work/<target>.rc (log in $work/<target>.log).
fuzz_target() {
  local exe=$1 target corpus log
  target=$(basename "$exe")
  target=${target#fuzz_}
  corpus=$work/$target
  mkdir -p "$corpus"
  cp "$src"/test/fuzz/seeds/"$target"/* "$corpus"/ 2>/dev/null || true
  while read -r f; do [ -n "$f" ] && [ -f "$f" ] && head -c $max_len "$f" > "$corpus/real-$(basename "$f")"; done < <(real_seeds "$target")
  # The config files of the repository are seeds for the YAML target.
  [ "$target" = yaml_params ] && cp "$src"/config/*.yaml "$corpus"/ 2>/dev/null
  log=$work/$target.log
  set +e
  ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    LSAN_OPTIONS="suppressions=$src/test/sanitizers/lsan.supp:print_suppressions=0" \
    "$exe" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 -max_len=$max_len \
    -print_final_stats=1 -artifact_prefix="$artifacts/$target-" >"$log" 2>&1
  echo $? > "$work/$target.rc"
  set -e
}

# The targets run side by side, one per core (each is single-threaded); reported in order below.
jobs=$(nproc)
for exe in "$build"/test/fuzz/fuzz_*; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  fuzz_target "$exe" &
done
wait

total=0
failed=()
printf '%-22s %12s %10s %s\n' target executions exec/s result
for exe in "$build"/test/fuzz/fuzz_*; do
  target=$(basename "$exe")
  target=${target#fuzz_}
  log=$work/$target.log
  rc=$(cat "$work/$target.rc" 2>/dev/null || echo 127)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  execs=${execs:-0}
  total=$((total + execs))
  if [ "$rc" -ne 0 ]; then
    failed+=("$target")
    printf '%-22s %12s %10s %s\n' "$target" "$execs" "${rate:-?}" "FAILED (rc $rc)"
    grep -E -m5 'ERROR|SUMMARY|terminate|what\(\)|Test unit written' "$log" || tail -20 "$log"
    # The input itself, so that a finding on another machine (CI) can be replayed from its log:
    # base64 -d > input && build-fuzz/test/fuzz/fuzz_<target> input
    for unit in $(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | head -1); do
      [ -f "$unit" ] && echo "input ($(stat -c %s "$unit") bytes, base64, first 6 KiB):" &&
        head -c 6144 "$unit" | base64 -w 100
    done
  else
    printf '%-22s %12s %10s %s\n' "$target" "$execs" "${rate:-?}" ok
  fi
done
echo "total executions: $total (${seconds} s per target, $jobs at a time)"
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzzing found problems in: ${failed[*]} (inputs in $artifacts)" >&2
  exit 1
fi
