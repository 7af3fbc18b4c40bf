// Integration on the simulator: a small world (2 x 2 city blocks, a short countryside loop, a
// street of identical facades) driven with same- and opposite-direction revisits. Keyframes every
// 10 m of the true path: render the scan, extract the peak cloud (Algorithm 1), undo the motion
// distortion with the true velocity, M2DP, query the database, verify every candidate. True loops
// must be found and almost no false loop accepted (the pose graph removes the rest).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "radarslam/loop/loop_detector.h"
#include "radarslam/loop/loop_verifier.h"
#include "radarslam/radar/motion_compensation.h"
#include "radarslam/radar/peak_cloud.h"
#include "radarslam/sim/simulator.h"

namespace radarslam {
namespace {

using mrpt::math::TPose2D;

TPose2D between(const TPose2D& a, const TPose2D& b) {  // b in the frame of a
  const double c = std::cos(a.phi), s = std::sin(a.phi), dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, std::remainder(b.phi - a.phi, 2 * M_PI)};
}

struct Keyframe {
  TPose2D truth;
  std::vector<RadarPoint> cloud;
  double travelled = 0;
};

TEST(LoopClosureOnSimulation, FindsTrueLoopsAndAcceptsAlmostNoFalseOne) {
  sim::SimulationConfig config;
  config.seed = 1;
  config.geometry.azimuths = 200;  // 1.8 degrees, 0.2 m x 600 bins = 120 m: fast to render
  config.geometry.bins = 600;
  config.geometry.range_resolution_m = 0.2;
  config.world.blocks_x = 2;
  config.world.blocks_y = 2;
  config.world.countryside_extent_m = 200;
  sim::Simulation sim(config);
  const Trajectory truth = sim.scanTruth();
  ASSERT_GT(truth.size(), 1000u);

  PeakCloudParams peaks;
  peaks.min_peak_distance_bins = 5;  // 1 m at 0.2 m bins (Oxford: 20 bins of 4.4 cm)
  LoopDetectorParams dp;
  dp.exclude_recent = 10;
  dp.exclude_recent_distance_m = 100;
  LoopDetector detector(dp);
  // A keyframe within 6 m (truth) is a loop the system should find. An accepted loop is false
  // when its relative pose is off by more than 2 m or 3 degrees (a correct pose between keyframes
  // 20 m apart is a valid loop edge).
  const double true_loop_m = 6.0;
  std::vector<Keyframe> kfs;
  CObservationRadarScan scan;
  double travelled = 0, since_kf = 1e9;
  int queries_with_true_loop = 0, retrieved = 0, verified = 0, candidates = 0, accepted = 0,
      false_accepted = 0;
  double max_pose_err_m = 0, max_pose_err_deg = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) {
      const double step =
          std::hypot(truth[i].pose.x - truth[i - 1].pose.x, truth[i].pose.y - truth[i - 1].pose.y);
      travelled += step, since_kf += step;
    }
    if (since_kf < 10.0) continue;
    since_kf = 0;
    sim.render(i, scan);
    // True body velocity over the sweep (from the route 50 ms either side).
    const StampNs t = truth[i].stamp;
    const TPose2D a = sim.truthAt(t - 50'000'000), b = sim.truthAt(t + 50'000'000);
    const TPose2D d = between(a, b);
    const BodyVelocity v{d.x / 0.1, d.y / 0.1, d.phi / 0.1};
    Keyframe kf{truth[i].pose, motionCompensated(extractPeakCloud(scan, peaks), scan, v), travelled};
    const std::vector<M2DPDescriptor> desc{computeM2DP(kf.cloud), computeM2DP(kf.cloud, {}, true)};

    // Ground truth: is there a database keyframe (outside the exclusion) at this place?
    bool has_true = false;
    for (std::size_t k = 0; k + dp.exclude_recent < kfs.size(); ++k)
      if (travelled - kfs[k].travelled >= dp.exclude_recent_distance_m &&
          std::hypot(kfs[k].truth.x - kf.truth.x, kfs[k].truth.y - kf.truth.y) < true_loop_m)
        has_true = true;
    queries_with_true_loop += has_true;

    bool any_true_retrieved = false, any_true_verified = false;
    for (const auto& c : detector.query(desc, travelled)) {
      const Keyframe& ck = kfs[c.keyframe];
      const double gt_dist = std::hypot(ck.truth.x - kf.truth.x, ck.truth.y - kf.truth.y);
      any_true_retrieved |= gt_dist < true_loop_m;
      ++candidates;
      const LoopVerification ver = verifyLoop(kf.cloud, ck.cloud);
      if (!ver.accepted) continue;
      ++accepted;
      const TPose2D gt = between(ck.truth, kf.truth);
      const double err_m = std::hypot(ver.relative_pose.x - gt.x, ver.relative_pose.y - gt.y);
      const double err_deg = std::abs(std::remainder(ver.relative_pose.phi - gt.phi, 2 * M_PI)) * 180 / M_PI;
      if (err_m > 2.0 || err_deg > 3.0) {
        ++false_accepted;
        std::cout << "[ false loop ] keyframe " << kfs.size() << " -> " << c.keyframe << " truth distance "
                  << gt_dist << " m, pose error " << err_m << " m " << err_deg << " deg; inliers "
                  << ver.inliers << " ratio " << ver.inlier_ratio << " rms " << ver.rms_m << " m, ambiguity "
                  << ver.ambiguity_ratio << "\n";
        continue;
      }
      max_pose_err_m = std::max(max_pose_err_m, err_m);
      max_pose_err_deg = std::max(max_pose_err_deg, err_deg);
      any_true_verified = true;
    }
    retrieved += has_true && any_true_retrieved;
    verified += has_true && any_true_verified;
    detector.add(desc[0], travelled);
    kfs.push_back(std::move(kf));
  }
  const double recall_retrieval = queries_with_true_loop ? double(retrieved) / queries_with_true_loop : 0;
  const double recall = queries_with_true_loop ? double(verified) / queries_with_true_loop : 0;
  const double precision = accepted ? double(accepted - false_accepted) / accepted : 1;
  std::printf(
      "[ simulation ] %zu keyframes, %d with a true loop; retrieval recall %.2f, verified recall %.2f; "
      "%d candidates, %d accepted, precision %.2f; max pose error %.2f m %.2f deg\n",
      kfs.size(), queries_with_true_loop, recall_retrieval, recall, candidates, accepted, precision,
      max_pose_err_m, max_pose_err_deg);
  EXPECT_GE(queries_with_true_loop, 20);
  // Geometry alone cannot tell look-alike places apart (this world has a street of identical
  // facades and right-angled blocks: a place can fit another one turned by 90 degrees), so a few
  // false loops pass verification; SLAM removes them with the pose graph's chi^2 test
  // (SlamOnSimulation.ClosesLoopsWithoutFalseOnesAndBeatsOdometry: none left in the graph).
  // Measured: 2 of 106 accepted (keyframes 209 and 246 to 57, 191 m apart, turned by 90 degrees).
  EXPECT_LE(false_accepted, 0.03 * accepted);
  EXPECT_GE(recall, 0.45);
}

}  // namespace
}  // namespace radarslam
