// Map save/load and export speed on a map of the size SLAM produces on a long drive: 1000
// keyframes x 1500 points (Algorithm-1 clouds), a 192-float M2DP descriptor each.
//   build-*/test/bench/bench_map
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <random>

#include <unistd.h>

#include <octomap/OcTree.h>

#include "radarslam/map/map_exports.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"

namespace fs = std::filesystem;
using namespace radarslam;

namespace {

// Keyframes every 2 m along a 2 km loop, points up to 80 m around each.
KeyframeMap bigMap(int keyframes, int points_per_keyframe) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> angle(0.f, 2 * float(M_PI)), range(3.f, 80.f), power(60.f, 255.f);
  KeyframeMap map;
  map.meta.created_ns = 1;
  for (int k = 0; k < keyframes; ++k) {
    Keyframe kf;
    kf.id = k;
    kf.stamp_ns = k * 250'000'000LL;
    const double t = 2 * M_PI * k / keyframes;
    kf.pose = {318.0 * std::cos(t), 318.0 * std::sin(t), t + M_PI / 2};
    for (int i = 0; i < points_per_keyframe; ++i) {
      const float a = angle(rng), r = range(rng);
      kf.points.push_back({r * std::cos(a), r * std::sin(a), power(rng)});
    }
    kf.descriptor.assign(192, 0.5f);
    if (k > 0)
      map.edges.push_back({std::uint64_t(k - 1),
                           std::uint64_t(k),
                           {2, 0, 0.0063},
                           {100, 0, 0, 0, 100, 0, 0, 0, 1000},
                           EdgeKind::Odometry});
    map.keyframes.push_back(std::move(kf));
  }
  return map;
}

struct BenchDir {
  fs::path path = fs::temp_directory_path() / ("radarslam_bench_map_" + std::to_string(::getpid()));
  ~BenchDir() { fs::remove_all(path); }
};

void BM_SaveMap(benchmark::State& state) {
  const KeyframeMap map = bigMap(static_cast<int>(state.range(0)), 1500);
  BenchDir dir;
  for (auto _ : state) saveMap(map, dir.path / "m");
  state.SetBytesProcessed(state.iterations() *
                          static_cast<std::int64_t>(fs::file_size(dir.path / "m" / "keyframes.bin")));
}
BENCHMARK(BM_SaveMap)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_LoadMap(benchmark::State& state) {
  BenchDir dir;
  saveMap(bigMap(static_cast<int>(state.range(0)), 1500), dir.path / "m");
  for (auto _ : state) benchmark::DoNotOptimize(loadMap(dir.path / "m"));
  state.SetBytesProcessed(state.iterations() *
                          static_cast<std::int64_t>(fs::file_size(dir.path / "m" / "keyframes.bin")));
}
BENCHMARK(BM_LoadMap)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_Sha256(benchmark::State& state) {
  const std::string data(1 << 24, 'x');
  for (auto _ : state) benchmark::DoNotOptimize(sha256Hex(data));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(data.size()));
}
BENCHMARK(BM_Sha256)->Unit(benchmark::kMillisecond);

void BM_ExportGrid(benchmark::State& state) {
  const KeyframeMap map = bigMap(static_cast<int>(state.range(0)), 1500);
  BenchDir dir;
  for (auto _ : state) exportOccupancyGrid(map, dir.path);
}
BENCHMARK(BM_ExportGrid)->Arg(1000)->Unit(benchmark::kMillisecond);

// The ray casting alone (buildOccupancy), which the grid and OctoMap layers, the exports and the
// map server share; its cells are the grid's width x height (bytes per cell: map_exports.h).
void BM_BuildOccupancy(benchmark::State& state) {
  const KeyframeMap map = bigMap(static_cast<int>(state.range(0)), 1500);
  std::size_t cells = 0;
  for (auto _ : state) {
    const OccupancyRaster r = buildOccupancy(map);
    cells = r.p_occupied.size();
    benchmark::DoNotOptimize(r.p_occupied.data());
  }
  state.counters["keyframes/s"] = benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)),
                                                     benchmark::Counter::kIsRate);
  state.counters["Mcells"] = static_cast<double>(cells) / 1e6;
}
BENCHMARK(BM_BuildOccupancy)->Arg(1000)->Unit(benchmark::kMillisecond);

// OctoMap layer (.bt + .ot), both fills (map_exports.h): keyframes/s is the issue-16 figure.
void BM_ExportOctomap(benchmark::State& state, OctomapExportParams::Fill fill) {
  const KeyframeMap map = bigMap(static_cast<int>(state.range(0)), 1500);
  BenchDir dir;
  OctomapExportParams params;
  params.fill = fill;
  for (auto _ : state) exportOctomap(map, dir.path, "map", params);
  state.counters["keyframes/s"] = benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)),
                                                     benchmark::Counter::kIsRate);
  state.counters["bt_MB"] = static_cast<double>(fs::file_size(dir.path / "map.bt")) / 1e6;
}
BENCHMARK_CAPTURE(BM_ExportOctomap, grid_columns, OctomapExportParams::Fill::grid_columns)
    ->Arg(50)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ExportOctomap, point_rays, OctomapExportParams::Fill::point_rays)
    ->Arg(50)
    ->Unit(benchmark::kMillisecond);

// How the two fills differ on the same map: of the voxels either one knows, the fraction both
// classify alike (occupied / free), and the voxels only one of them knows.
void BM_OctomapFillAgreement(benchmark::State& state) {
  const KeyframeMap map = bigMap(static_cast<int>(state.range(0)), 1500);
  BenchDir dir;
  OctomapExportParams rays;
  rays.fill = OctomapExportParams::Fill::point_rays;
  exportOctomap(map, dir.path, "rays", rays);
  exportOctomap(map, dir.path, "cols");
  const octomap::OcTree a((dir.path / "rays.bt").string()), b((dir.path / "cols.bt").string());
  double same = 0, differ = 0, only_rays = 0, only_cols = 0;
  for (auto _ : state) {
    same = differ = only_rays = only_cols = 0;
    for (auto it = a.begin_leafs(); it != a.end_leafs(); ++it) {
      const auto* n = b.search(it.getKey());
      if (n == nullptr)
        ++only_rays;
      else
        (a.isNodeOccupied(*it) == b.isNodeOccupied(n) ? same : differ) += 1;
    }
    for (auto it = b.begin_leafs(); it != b.end_leafs(); ++it)
      if (a.search(it.getKey()) == nullptr) ++only_cols;
  }
  state.counters["agree"] = same / (same + differ);
  state.counters["only_rays"] = only_rays;
  state.counters["only_cols"] = only_cols;
  state.counters["both"] = same + differ;
}
BENCHMARK(BM_OctomapFillAgreement)->Arg(50)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_ExportCloudAndSimplemap(benchmark::State& state) {
  const KeyframeMap map = bigMap(static_cast<int>(state.range(0)), 1500);
  BenchDir dir;
  for (auto _ : state) {
    exportPointCloud(map, dir.path);
    exportSimpleMap(map, dir.path);
  }
}
BENCHMARK(BM_ExportCloudAndSimplemap)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
