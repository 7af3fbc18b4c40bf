// Localisation timings on the synthetic street world of test/reloc (151 keyframes, ~600 points per
// scan): submap build, scan-to-submap tracking, global localisation (retrieval + verification).
// The odometry that runs per scan as well is measured in bench_frontend.
#include <benchmark/benchmark.h>

#include "../reloc/synthetic_world.h"
#include "radarslam/reloc/global_localizer.h"
#include "radarslam/reloc/map_tracker.h"

namespace radarslam {
namespace {

const test::SyntheticWorld& world() {
  static const test::SyntheticWorld w = test::SyntheticWorld::make(7);
  return w;
}
const KeyframeMap& map() {
  static const KeyframeMap m = world().map();
  return m;
}

void BM_SubmapBuild(benchmark::State& state) {
  const SubmapParams params;
  for (auto _ : state) benchmark::DoNotOptimize(LocalSubmap::build(map(), 150, 0, params));
  state.counters["points"] = static_cast<double>(LocalSubmap::build(map(), 150, 0, params).size());
}
BENCHMARK(BM_SubmapBuild)->Unit(benchmark::kMillisecond);

void BM_TrackScan(benchmark::State& state) {
  MapTracker tracker(map());
  const mrpt::math::TPose2D truth{151.3, 2.0, 0.02};
  const auto cloud = world().scan(truth, 77);
  const mrpt::math::TPose2D predicted{151.8, 1.7, 0.03};
  tracker.track(cloud, predicted);  // builds the submap once
  for (auto _ : state) benchmark::DoNotOptimize(tracker.track(cloud, predicted));
  state.counters["scan_points"] = static_cast<double>(cloud.size());
}
BENCHMARK(BM_TrackScan)->Unit(benchmark::kMillisecond);

void BM_GlobalLocalize(benchmark::State& state) {
  static const GlobalLocalizer global(map());
  const auto cloud = world().scan({101.0, 1.3, 0.35}, 99);
  for (auto _ : state) benchmark::DoNotOptimize(global.localize(cloud));
}
BENCHMARK(BM_GlobalLocalize)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace radarslam

BENCHMARK_MAIN();
