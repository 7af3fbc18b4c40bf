// The full SLAM pipeline on the simulator's demo world, rendered in memory (no disk, so a long
// run needs no 6 GB dataset): scans/s of RadarSlam::process + finish() with 3 threads, and the
// process's peak resident memory, for a short and a 10 000-scan run (memory must stay bounded:
// keyframes keep only their peak cloud and descriptor, never a scan image).
//   build/test/bench/bench_slam                         # both sizes
//   build/test/bench/bench_slam --benchmark_filter=/2000
// Each size runs in its own process for a meaningful peak RSS: use --benchmark_filter.
#include <benchmark/benchmark.h>

#include <chrono>
#include <fstream>
#include <string>

#include "radarslam/sim/simulator.h"
#include "radarslam/slam/radar_slam.h"

namespace {

double peakRssMiB() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0;
}

void BM_SlamSimulated(benchmark::State& state) {
  const auto scans = static_cast<std::size_t>(state.range(0));
  radarslam::sim::SimulationConfig config;
  config.scans = static_cast<int>(scans);
  radarslam::sim::Simulation sim(config);
  radarslam::CObservationRadarScan scan;
  for (auto _ : state) {
    radarslam::RadarSlam slam;  // defaults = config/oxford.yaml's front end, 3 threads
    double render_s = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < sim.numScans(); ++i) {
      const auto r0 = std::chrono::steady_clock::now();
      sim.render(i, scan);
      render_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
      slam.process(scan);
    }
    slam.finish();
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto stats = slam.stats();
    state.counters["scans"] = static_cast<double>(sim.numScans());
    state.counters["slam_scans_per_s"] = static_cast<double>(sim.numScans()) / (total_s - render_s);
    state.counters["with_render_scans_per_s"] = static_cast<double>(sim.numScans()) / total_s;
    state.counters["keyframes"] = static_cast<double>(stats.keyframes);
    state.counters["loops"] = static_cast<double>(stats.loops_accepted);
    state.counters["peak_rss_MiB"] = peakRssMiB();
  }
}
BENCHMARK(BM_SlamSimulated)->Arg(2000)->Arg(10000)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
