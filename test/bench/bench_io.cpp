// Decoding speed of the dataset readers: Oxford polar PNGs (real tiny sample; skipped if the
// shared data is absent), and reading a converted .rawlog back.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "radarslam/io/dataset.h"
#include "radarslam/io/rawlog_writer.h"
#include "shared_data.h"

using namespace radarslam;

namespace {
const std::filesystem::path kOxford = test::realDataDir() / "oxford_radar_robotcar_tiny";

void BM_DecodeOxfordPng(benchmark::State& state) {
  if (!std::filesystem::exists(kOxford)) {
    state.SkipWithError("real data not found (../shared/data/real/oxford_radar_robotcar_tiny)");
    return;
  }
  const auto reader = openDataset(kOxford);
  std::size_t i = 0;
  for (auto _ : state) {
    auto scan = reader->readScan(i++ % reader->size());
    benchmark::DoNotOptimize(scan->power.data());
  }
  state.counters["scans/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DecodeOxfordPng)->Unit(benchmark::kMillisecond);

void BM_ReadRawlogSequentially(benchmark::State& state) {
  if (!std::filesystem::exists(kOxford)) {
    state.SkipWithError("real data not found (../shared/data/real/oxford_radar_robotcar_tiny)");
    return;
  }
  const auto file = std::filesystem::temp_directory_path() / "radarslam_bench_io.rawlog";
  {
    const auto src = openDataset(kOxford);
    RawlogWriter w(file);
    for (std::size_t i = 0; i < src->size(); ++i) w.write(*src->readScan(i));
  }
  const auto reader = openDataset(file);
  std::size_t i = 0;
  for (auto _ : state) {
    auto scan = reader->readScan(i++ % reader->size());
    benchmark::DoNotOptimize(scan->power.data());
  }
  state.counters["scans/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  std::filesystem::remove(file);
}
BENCHMARK(BM_ReadRawlogSequentially)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
