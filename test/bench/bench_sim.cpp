// Simulator speed at Oxford geometry (400 x 3768): render only, and render + Oxford PNG encode
// (compression 1). Run: build/test/bench/bench_sim   (scans/s = items_per_second)
#include <benchmark/benchmark.h>

#include "radarslam/io/oxford_writer.h"
#include "radarslam/sim/simulator.h"

using namespace radarslam;

namespace {
sim::Simulation& simulation() {
  static sim::Simulation s([] {
    sim::SimulationConfig c;
    c.scans = 400;
    return c;
  }());
  return s;
}

void BM_RenderScan(benchmark::State& state) {
  auto& sim = simulation();
  CObservationRadarScan scan;
  std::size_t i = 40;
  for (auto _ : state) {
    sim.render(i, scan);
    i = i + 1 < sim.numScans() ? i + 1 : 40;
    benchmark::DoNotOptimize(scan.power.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RenderScan)->Unit(benchmark::kMillisecond);

void BM_RenderAndEncodePng(benchmark::State& state) {
  auto& sim = simulation();
  CObservationRadarScan scan;
  std::size_t i = 40, bytes = 0;
  for (auto _ : state) {
    sim.render(i, scan);
    i = i + 1 < sim.numScans() ? i + 1 : 40;
    bytes += encodeOxfordPng(scan, 1).size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["png_kB"] = static_cast<double>(bytes) / 1024.0 / static_cast<double>(state.iterations());
}
BENCHMARK(BM_RenderAndEncodePng)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
