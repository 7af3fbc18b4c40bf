// Evaluation cost on an Oxford-sized run (9000 poses at 4 Hz, ~9 km): the full evaluate() (association,
// KITTI metric, ATE, RPE), the KITTI metric alone, and writing the four plot files.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>

#include "radarslam/eval/evaluate.h"
#include "radarslam/eval/plots.h"

using namespace radarslam;

namespace {
Trajectory drive(std::size_t n, double scale) {
  Trajectory t{{0, {}}};
  for (std::size_t k = 1; k < n; ++k)
    t.push_back({static_cast<StampNs>(k) * 250'000'000,
                 t.back().pose +
                     mrpt::math::TPose2D(1.0 * scale, 0, 0.05 * std::sin(0.013 * static_cast<double>(k)))});
  return t;
}
const Trajectory kGt = drive(9000, 1.0);
const Trajectory kEst = drive(9000, 1.01);
}  // namespace

static void BM_Evaluate(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(eval::evaluate(kEst, kGt));
}
BENCHMARK(BM_Evaluate)->Unit(benchmark::kMillisecond);

static void BM_KittiMetric(benchmark::State& state) {
  std::vector<mrpt::math::TPose2D> gt, est;
  for (std::size_t i = 0; i < kGt.size(); ++i) gt.push_back(kGt[i].pose), est.push_back(kEst[i].pose);
  eval::KittiParams params;
  params.step_frames = static_cast<unsigned>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(eval::computeKittiMetric(gt, est, params));
}
BENCHMARK(BM_KittiMetric)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

static void BM_WritePlots(benchmark::State& state) {
  const eval::EvalReport report = eval::evaluate(kEst, kGt);
  const auto dir = std::filesystem::temp_directory_path() / "radarslam_bench_eval_plots";
  for (auto _ : state) benchmark::DoNotOptimize(eval::writePlots(dir, report));
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_WritePlots)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
