// Loop closure and back end timings: M2DP per cloud, retrieval per query in a 1000-keyframe
// database, verification per candidate, pose-graph optimisation of 1000 nodes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "../loop/synthetic_world.h"
#include "radarslam/backend/pose_graph.h"
#include "radarslam/loop/loop_detector.h"
#include "radarslam/loop/loop_verifier.h"

namespace radarslam {
namespace {

const looptest::PointWorld& world() {
  static const looptest::PointWorld w = looptest::randomWorld(1, 600);
  return w;
}

// Arg = points per metre of wall: 1.5 gives ~400 points (simulator-like), 4 ~1000 (Oxford-like).
void BM_M2DP(benchmark::State& state) {
  const auto cloud = looptest::observe(world(), 0, 0, 0, 1, 80, static_cast<double>(state.range(0)) / 2.0);
  for (auto _ : state) benchmark::DoNotOptimize(computeM2DP(cloud));
  state.counters["points"] = static_cast<double>(cloud.size());
}
BENCHMARK(BM_M2DP)->Arg(3)->Arg(8)->Unit(benchmark::kMillisecond);

void BM_RetrievalQuery1000Keyframes(benchmark::State& state) {
  static LoopDetector* db = [] {
    auto* d = new LoopDetector();
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> pos(-500, 500), yaw(-M_PI, M_PI);
    for (int i = 0; i < 1000; ++i)
      d->add(computeM2DP(
                 looptest::observe(world(), pos(rng), pos(rng), yaw(rng), 10 + static_cast<unsigned>(i))),
             10.0 * i);
    return d;
  }();
  const auto cloud = looptest::observe(world(), 100, 100, 1.0, 3);
  const std::vector<M2DPDescriptor> q{computeM2DP(cloud), computeM2DP(cloud, {}, true)};
  std::size_t found = 0;
  for (auto _ : state) found += db->query(q, 1e6).size();
  state.counters["candidates"] = static_cast<double>(found) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_RetrievalQuery1000Keyframes)->Unit(benchmark::kMicrosecond);

void BM_VerifyCandidate(benchmark::State& state) {
  const double density = static_cast<double>(state.range(0)) / 2.0;
  const auto a = looptest::observe(world(), 20, -30, 0.4, 1, 80, density);
  const auto b = looptest::observe(world(), 16, -28.5, 0.4 + M_PI, 2, 80, density);
  bool accepted = false;
  for (auto _ : state) accepted = verifyLoop(b, a).accepted;
  state.counters["points"] = static_cast<double>(a.size());
  state.counters["accepted"] = accepted;
}
BENCHMARK(BM_VerifyCandidate)->Arg(3)->Arg(8)->Unit(benchmark::kMillisecond);

// 1000 nodes on 10 laps of a 100-node square with yaw drift, a loop edge per lap.
void BM_PoseGraph(benchmark::State& state) {  // Arg: nodes (a 2 m grid walk, a loop edge every 100)
  const auto nodes = static_cast<std::size_t>(state.range(0));
  std::size_t rejected = 0;
  for (auto _ : state) {
    state.PauseTiming();
    PoseGraph g;
    std::mt19937 rng(4);
    std::normal_distribution<double> n(0, 0.01);
    const Eigen::Matrix3d info = Eigen::Vector3d(400, 400, 10000).asDiagonal();
    mrpt::math::TPose2D est{0, 0, 0};
    g.addNode(est);
    for (std::size_t i = 1; i < nodes; ++i) {
      const mrpt::math::TPose2D z{2.0 + n(rng), n(rng), (i % 25 == 0 ? M_PI / 2 : 0.0) + 0.001 + n(rng)};
      const double c = std::cos(est.phi), s = std::sin(est.phi);
      est = {est.x + c * z.x - s * z.y, est.y + s * z.x + c * z.y, est.phi + z.phi};
      g.addNode(est);
      g.addOdometryEdge(i - 1, i, z, info);
      if (i % 100 == 0) g.addLoopEdge(i - 100, i, {0, 0, 0}, info);
    }
    state.ResumeTiming();
    rejected += g.optimize().rejected_edges.size();
  }
  state.counters["rejected"] = static_cast<double>(rejected) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_PoseGraph)->Arg(1000)->Arg(4000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace radarslam

BENCHMARK_MAIN();
