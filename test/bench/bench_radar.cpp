// Radar-image processing speed: polar->Cartesian per scan at Oxford geometry (400 x 3768 bins ->
// 701 x 701 at 0.25 m/px, and 1000 x 1000), the remap-table rebuild, Algorithm 1 per scan, and
// read (PNG decode via openDataset) + Cartesian in scans/s on the real Oxford tiny sequence.
// Each runs with OpenCV on 1 thread (threads:1) and with OpenCV's default pool (threads:0).
//
//   build-*/test/bench/bench_radar --benchmark_min_time=0.5
#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>

#include <radarslam/io/dataset.h>
#include <radarslam/obs/registration.h>
#include <radarslam/radar/cartesian.h>
#include <radarslam/radar/peak_cloud.h>

namespace {

using namespace radarslam;

std::filesystem::path oxfordTiny() {
  const char* env = std::getenv("RADARSLAM_SHARED_DIR");
  const std::filesystem::path shared = env ? env : RADARSLAM_SHARED_DIR;
  return shared / "data" / "real" / "oxford_radar_robotcar_tiny";
}

void setThreads(const benchmark::State& state) { cv::setNumThreads(state.range(0) == 1 ? 1 : -1); }

// Oxford CTS350-X geometry: speckle (0..39) plus 20 returns of 60..199 per azimuth, each 5 bins
// long (remap cost does not depend on content; the peak cloud's does a little).
CObservationRadarScan oxfordLikeScan(double angle_jitter = 0.0) {
  CObservationRadarScan s;
  s.resize(400, 3768);
  s.range_resolution_m = 0.0432;
  s.range_offset_m = 0.0216;
  std::mt19937 rng(7);
  for (auto& p : s.power) p = static_cast<std::uint8_t>(rng() % 40);
  for (std::uint32_t a = 0; a < 400; ++a)
    for (int k = 0; k < 20; ++k) {
      const std::uint32_t bin = 60 + rng() % 3700;
      const auto power = static_cast<std::uint8_t>(60 + rng() % 140);
      for (std::uint32_t b = bin; b < bin + 5; ++b) s.row(a)[b] = power;
    }
  for (std::uint32_t i = 0; i < 400; ++i) {
    s.azimuth_angles_rad[i] =
        (13.0 + 14.0 * i) / 5600.0 * 2.0 * std::numbers::pi + angle_jitter * std::sin(i);
    s.azimuth_stamps_ns[i] = 1'547'131'046'353'776'000 + static_cast<StampNs>(i) * 625'000;
  }
  s.updateReferenceTime();
  return s;
}

void BM_Cartesian(benchmark::State& state) {
  setThreads(state);
  CartesianParams params;
  params.size_px = static_cast<int>(state.range(1));
  params.m_per_px = 0.25;
  params.fixed_point_maps = state.range(2) != 0;
  const PolarToCartesian conv(params);
  const auto scan = oxfordLikeScan();
  cv::Mat out;
  conv.convert(scan, out);  // tables built once, outside the timing
  for (auto _ : state) {
    conv.convert(scan, out);
    benchmark::DoNotOptimize(out.data);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(params.fixed_point_maps ? "fixed-point maps" : "float maps");
}
BENCHMARK(BM_Cartesian)
    ->ArgNames({"threads", "px", "fixed"})
    ->ArgsProduct({{1, 0}, {701, 1000}, {1, 0}})
    ->Unit(benchmark::kMillisecond);

// Every scan with different azimuth angles (e.g. Boreas wobble): tables are rebuilt each time.
void BM_CartesianRebuild(benchmark::State& state) {
  setThreads(state);
  const PolarToCartesian conv(CartesianParams{});
  const auto a = oxfordLikeScan(0.0), b = oxfordLikeScan(1e-4);
  cv::Mat out;
  bool flip = false;
  for (auto _ : state) {
    conv.convert(flip ? a : b, out);
    flip = !flip;
    benchmark::DoNotOptimize(out.data);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CartesianRebuild)->ArgNames({"threads"})->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_PeakCloudSynthetic(benchmark::State& state) {
  const auto scan = oxfordLikeScan();
  std::size_t points = 0;
  for (auto _ : state) {
    const auto cloud = extractPeakCloud(scan);
    points = cloud.size();
    benchmark::DoNotOptimize(cloud.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_PeakCloudSynthetic)->Unit(benchmark::kMillisecond);

void BM_PeakCloudOxford(benchmark::State& state) {
  if (!std::filesystem::exists(oxfordTiny())) {
    state.SkipWithError("real Oxford data not found (../shared/data/real/oxford_radar_robotcar_tiny)");
    return;
  }
  const auto reader = openDataset(oxfordTiny());
  std::vector<CObservationRadarScan::Ptr> scans;
  for (std::size_t i = 0; i < reader->size(); ++i) scans.push_back(reader->readScan(i));
  std::size_t k = 0, points = 0;
  for (auto _ : state) {
    const auto cloud = extractPeakCloud(*scans[k++ % scans.size()]);
    points += cloud.size();
    benchmark::DoNotOptimize(cloud.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["points/scan"] = static_cast<double>(points) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_PeakCloudOxford)->Unit(benchmark::kMillisecond);

void BM_ReadAndCartesianOxford(benchmark::State& state) {
  setThreads(state);
  if (!std::filesystem::exists(oxfordTiny())) {
    state.SkipWithError("real Oxford data not found (../shared/data/real/oxford_radar_robotcar_tiny)");
    return;
  }
  const auto reader = openDataset(oxfordTiny());
  const PolarToCartesian conv(CartesianParams{});
  cv::Mat out;
  std::size_t k = 0;
  for (auto _ : state) {
    const auto scan = reader->readScan(k++ % reader->size());
    conv.convert(*scan, out);
    benchmark::DoNotOptimize(out.data);
  }
  state.SetItemsProcessed(state.iterations());  // items/s = scans/s
}
BENCHMARK(BM_ReadAndCartesianOxford)->ArgNames({"threads"})->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  radarslam::registerRadarslamClasses();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
