#!/usr/bin/env bash
# CI hardening stage (docs/hardening.md), run by .ci/run after scripts/test.sh.
# ONE clang-14 build (build-hardening/, -O1 -g, benchmarks off) compiles our code with
# ASan + UBSan (+ LSan) and libFuzzer coverage (-fsanitize=fuzzer-no-link); the test programs
# link the sanitizers only, the fuzz programs also link libFuzzer's main(). Then:
#   1. the whole ctest suite under the sanitizers (any report aborts the test -> failure),
#   2. a bounded libFuzzer run of every target (scripts/fuzz.sh), failing on any finding.
# Usage: scripts/ci-hardening.sh [fuzz-seconds-per-target] [build-dir]   (default 10 s)
set -euo pipefail
cd "$(dirname "$0")/.."
src=$PWD
seconds=${1:-10}
build=${2:-build-hardening}
jobs=$(nproc)

# clang-14 and its sanitizer/libFuzzer runtimes (Debian bookworm), installed only when missing.
missing=()
for p in clang-14 libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "ci-hardening: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

t0=$(date +%s)
if [ ! -f "$build/build.ninja" ]; then
  # Warnings: GCC's -Werror build in scripts/test.sh owns them; clang only checks here.
  # -gline-tables-only: file:line in sanitizer reports at two thirds of the compile time of -g.
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DRADARSLAM_SANITIZE=address,undefined -DRADARSLAM_BUILD_FUZZERS=ON \
    -DRADARSLAM_BUILD_BENCHMARKS=OFF -DRADARSLAM_WERROR=OFF >/dev/null
fi
cmake --build "$build" -j"$jobs"
t1=$(date +%s)

# detect_leaks: LSan at exit; abort_on_error: a report kills the test (ctest sees a failure).
# Suppressions are narrowly scoped third-party entries, each with a reason (test/sanitizers/).
(
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  export LSAN_OPTIONS="suppressions=$src/test/sanitizers/lsan.supp:print_suppressions=0"
  # Process timeouts in the multi-process tests (test/dds/dds_test_util.h) only bound hangs; the
  # instrumented binaries are ~5x slower, so they get 4x the time.
  export RADARSLAM_TEST_TIME_SCALE=4
  # The simulated drives the tests share (test/support/simulated_dataset.h) come from the Release
  # build's program when the Release stage built it (.ci/run): same drives, a quarter of the time.
  [ -x "$src/build/apps/radarslam" ] && export RADARSLAM_TEST_SIMULATOR="$src/build/apps/radarslam"
  cd "$build"
  # Excluded here, and only these (all run in the Release stage, scripts/test.sh; CI time budget):
  # - the whole-system SLAM runs on a simulated drive (SlamOnSimulation.*,
  #   test/slam/test_radar_slam_sim.cpp): > 7 min each under ASan+UBSan on 2 cores; every unit test
  #   of the same modules runs here, and the pipeline itself through the odometry, loop-closure, map
  #   and CLI tests;
  # - LocalizeIntegrity.DriveOutOfTheMapAndBack and ...WithAdaptiveOdometryRadius (~200 s and ~190 s
  #   here): the localiser's paths they take (loss, dead-reckoned prior, the chi^2 gate on a global
  #   fix after a loss) run here in LocalizeIntegrity.KidnappedVehicleIsNeverTrustedWhileWrong and
  #   the other LocalizeIntegrity tests; the look-alike fix the gate must reject is their accuracy
  #   case, checked in the Release stage;
  # - CliKillWrite.KilledOverwriteLeavesThePreviousOrTheNewMap (~150 s): kills the program mid-save
  #   to test the file protocol's crash safety; the same save code runs here in the CliMap tests.
  # - LocalizeCli.InASlamMapTheCompensatedCloudsAreUsedAsStored: an accuracy test (SLAM map of 130
  #   scans + localisation); its code paths run here in the other LocalizeCli and CliMap tests.
  # - LocalizeIntegrity.AMapThatDisagreesWithItselfIsNotTrustedWhereItDisagrees (~125 s here): an
  #   accuracy test; check (i) runs here in every other localisation test (it is always on) and in
  #   the unit tests Reloc.AMapThatDisagrees* and Reloc.AKeyframeOutOfPlace*.
  heavy='^SlamOnSimulation\.|^LocalizeCli\.InASlamMap|^LocalizeIntegrity\.DriveOutOfTheMapAndBack|^LocalizeIntegrity\.AMapThatDisagrees|^CliKillWrite\.KilledOverwriteLeavesThePreviousOrTheNewMap$'
  ctest -j"$jobs" --output-on-failure --timeout 1800 -E "$heavy"
)
t2=$(date +%s)

bash scripts/fuzz.sh "$seconds" "$build"
t3=$(date +%s)
echo "hardening stage: build $((t1 - t0)) s, sanitizer tests $((t2 - t1)) s," \
  "fuzzing $((t3 - t2)) s (${seconds} s per target), total $((t3 - t0)) s on $jobs cores"
