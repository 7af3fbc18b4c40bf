// Per-scan cost of the radar odometry on the 11 real Oxford tiny scans, split by stage (Cartesian,
// detect, describe, match, clique, SVD, refine) plus the whole tracker. One thread (OpenCV too):
//   build-*/test/bench/bench_frontend
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>

#include <cmath>

#include "radarslam/core/yaml_params.h"
#include "radarslam/frontend/consistency_graph.h"
#include "radarslam/frontend/odometry.h"
#include "radarslam/frontend/pose_refiner.h"
#include "radarslam/frontend/svd_pose.h"
#include "radarslam/io/dataset.h"
#include "shared_data.h"

using namespace radarslam;

namespace {

struct Data {
  OdometryParams params;
  std::vector<CObservationRadarScan::Ptr> scans;
  std::vector<cv::Mat> images;
  std::vector<std::vector<cv::KeyPoint>> detected;
  std::vector<FeatureSet> features;
  std::vector<AlignImage> aligned;
  std::vector<ImageKeypoints> keypoints;
  std::vector<Correspondences> matches;  ///< pair i -> i+1, before outlier rejection
  std::vector<Correspondences> inliers;  ///< after eq. (3) + clique
  std::vector<mrpt::math::TPose2D> poses;
};

const Data& data() {
  static const Data d = [] {
    cv::setNumThreads(1);
    Data out;
    loadParams(YamlParams::fromFile(std::string(RADARSLAM_SOURCE_DIR) + "/config/oxford.yaml"), out.params);
    const auto reader = openDataset(test::realDataDir() / "oxford_radar_robotcar_tiny");
    const PolarToCartesian conv(out.params.cartesian);
    const KeypointExtractor kx(out.params.keypoints);
    for (std::size_t i = 0; i < reader->size(); ++i) {
      out.scans.push_back(reader->readScan(i));
      out.images.push_back(conv.convert(*out.scans.back()));
      out.detected.push_back(kx.detect(out.images.back()));
      out.keypoints.push_back(kx.describe(out.images.back(), out.detected.back()));
      out.aligned.push_back(prepareAlignImage(out.images.back(), out.params.patch_alignment));
      FeatureSet f;
      for (const auto& kp : out.keypoints.back().points) {
        const auto m = conv.pixelToMetres(kp.pt.x, kp.pt.y);
        f.xy.emplace_back(m.x, m.y);
      }
      f.descriptors = out.keypoints.back().descriptors;
      f.norm_type = out.keypoints.back().norm_type;
      out.features.push_back(f);
    }
    for (std::size_t i = 0; i + 1 < out.features.size(); ++i) {
      // Prior: ~2 m forward (the vehicle's speed here); the tracker uses its velocity instead.
      out.matches.push_back(matchWithinRadius(out.features[i + 1], out.features[i], {2.0, 0, 0},
                                              out.params.matching.radius_m, out.params.matching));
      const auto c = maximumClique(buildConsistencyGraph(out.matches.back(), out.params.outliers.delta_c_m));
      Correspondences in;
      for (int v : c.vertices) in.push_back(out.matches.back()[v]);
      out.inliers.push_back(in);
      out.poses.push_back(*fitPoseSvd(in));
    }
    return out;
  }();
  return d;
}

}  // namespace

static void BM_Cartesian(benchmark::State& state) {
  const auto& d = data();
  const PolarToCartesian conv(d.params.cartesian);
  cv::Mat out;
  conv.convert(*d.scans[0], out);  // builds the remap tables once
  std::size_t i = 0;
  for (auto _ : state) conv.convert(*d.scans[i++ % d.scans.size()], out);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Cartesian)->Unit(benchmark::kMillisecond);

static void BM_Detect(benchmark::State& state) {
  const auto& d = data();
  const KeypointExtractor kx(d.params.keypoints);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(kx.detect(d.images[i++ % d.images.size()]));
}
BENCHMARK(BM_Detect)->Unit(benchmark::kMillisecond);

static void BM_Describe(benchmark::State& state) {
  const auto& d = data();
  const KeypointExtractor kx(d.params.keypoints);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % d.images.size();
    benchmark::DoNotOptimize(kx.describe(d.images[k], d.detected[k]));
  }
}
BENCHMARK(BM_Describe)->Unit(benchmark::kMillisecond);

static void BM_AlignPrep(benchmark::State& state) {
  const auto& d = data();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(prepareAlignImage(d.images[i++ % d.images.size()], d.params.patch_alignment));
}
BENCHMARK(BM_AlignPrep)->Unit(benchmark::kMillisecond);

static void BM_Match(benchmark::State& state) {
  const auto& d = data();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % d.matches.size();
    benchmark::DoNotOptimize(matchWithinRadius(d.features[k + 1], d.features[k], {2.0, 0, 0},
                                               d.params.matching.radius_m, d.params.matching));
  }
}
BENCHMARK(BM_Match)->Unit(benchmark::kMillisecond);

static void BM_Clique(benchmark::State& state) {  // eq. (3) graph + maximum clique
  const auto& d = data();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& m = d.matches[i++ % d.matches.size()];
    benchmark::DoNotOptimize(maximumClique(buildConsistencyGraph(m, d.params.outliers.delta_c_m),
                                           d.params.outliers.max_clique_steps));
  }
}
BENCHMARK(BM_Clique)->Unit(benchmark::kMillisecond);

static void BM_Svd(benchmark::State& state) {
  const auto& d = data();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(fitPoseSvd(d.inliers[i++ % d.inliers.size()]));
}
BENCHMARK(BM_Svd)->Unit(benchmark::kMicrosecond);

static void BM_PatchAlignInliers(benchmark::State& state) {  // part of the refine stage
  const auto& d = data();
  std::size_t i = 0, n = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % d.inliers.size();
    for (const auto& c : d.inliers[k]) {
      benchmark::DoNotOptimize(alignPatch(d.aligned[k], d.keypoints[k].points[c.ref_index].pt,
                                          d.aligned[k + 1], d.keypoints[k + 1].points[c.cur_index].pt,
                                          d.params.patch_alignment));
      ++n;
    }
  }
  state.counters["aligned/s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PatchAlignInliers)->Unit(benchmark::kMillisecond);

static void BM_RefinePose(benchmark::State& state) {  // eq. (4) Gauss-Newton on the inliers
  const auto& d = data();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % d.inliers.size();
    benchmark::DoNotOptimize(refinePose(d.inliers[k], d.poses[k], d.params.refine));
  }
}
BENCHMARK(BM_RefinePose)->Unit(benchmark::kMicrosecond);

/// The whole tracker, per scan (items/s = scans/s). Each iteration tracks scans 1..10 after an
/// untimed start on scan 0 (remap tables and first keyframe).
static void BM_TrackerPerScan(benchmark::State& state) {
  const auto& d = data();
  for (auto _ : state) {
    state.PauseTiming();
    RadarOdometry odo(d.params);
    odo.process(*d.scans[0]);
    state.ResumeTiming();
    for (std::size_t i = 1; i < d.scans.size(); ++i) benchmark::DoNotOptimize(odo.process(*d.scans[i]));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(d.scans.size() - 1));
}
BENCHMARK(BM_TrackerPerScan)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
