// The whole system on the simulator (a small world: 2 x 2 city blocks, countryside, the street of
// identical facades; a reduced radar of 200 azimuths x 600 bins x 0.2 m so it runs in seconds):
// loops are closed, none of them false, SLAM beats odometry, the map is consistent with the
// trajectory, and one thread gives the same result twice.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "radarslam/eval/evaluate.h"
#include "radarslam/sim/simulator.h"
#include "radarslam/slam/loop_evaluation.h"
#include "radarslam/slam/radar_slam.h"

namespace radarslam {
namespace {

sim::SimulationConfig smallWorld() {
  sim::SimulationConfig config;
  config.seed = 1;
  config.geometry.azimuths = 200;
  config.geometry.bins = 600;
  config.geometry.range_resolution_m = 0.2;
  config.world.blocks_x = 2;
  config.world.blocks_y = 2;
  config.world.countryside_extent_m = 200;
  return config;
}

SlamParams smallRadarParams(int threads) {
  SlamParams p;
  p.threads = threads;
  p.odometry.cartesian.size_px = 481;  // +-120 m at 0.5 m/px: the reduced radar's range
  p.odometry.cartesian.m_per_px = 0.5;
  p.loop_closing.peak_cloud.min_peak_distance_bins = 5;  // 1 m (Oxford: 20 bins of 4.3 cm)
  p.loop_closing.detector.exclude_recent = 10;
  p.loop_closing.detector.exclude_recent_distance_m = 100;
  p.loop_closing.drift_fraction = 0.15;  // the reduced radar drifts ~5 % and turns ~0.02 deg/m
  p.loop_closing.drift_deg_per_m = 0.05;
  return p;
}

struct SlamRun {
  Trajectory trajectory, odometry;
  KeyframeMap map;
  std::vector<LoopRecord> loops;
  SlamStats stats;
};

SlamRun runSlam(sim::Simulation& sim, std::size_t scans, int threads) {
  RadarSlam slam(smallRadarParams(threads));
  CObservationRadarScan scan;
  for (std::size_t i = 0; i < scans; ++i) {
    sim.render(i, scan);
    slam.process(scan);
  }
  slam.finish();
  return {slam.trajectory(), slam.odometryTrajectory(), slam.map(), slam.loops(), slam.stats()};
}

class SlamOnSimulation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sim_ = new sim::Simulation(smallWorld());
    truth_ = new Trajectory(sim_->scanTruth());
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete truth_;
  }
  static sim::Simulation* sim_;
  static Trajectory* truth_;
};
sim::Simulation* SlamOnSimulation::sim_ = nullptr;
Trajectory* SlamOnSimulation::truth_ = nullptr;

TEST_F(SlamOnSimulation, ClosesLoopsWithoutFalseOnesAndBeatsOdometry) {
  const SlamRun run = runSlam(*sim_, sim_->numScans(), 1);
  const eval::EvalReport slam = eval::evaluate(run.trajectory, *truth_);
  const eval::EvalReport odo = eval::evaluate(run.odometry, *truth_);
  LoopEvaluationParams lp;
  lp.exclude_recent = 10;
  lp.exclude_recent_distance_m = 100;
  const LoopEvaluation le = evaluateLoops(run.map, run.loops, *truth_, lp);
  std::printf(
      "[ slam ] %zu scans, %zu keyframes, %zu map points; loops: %zu verified, %zu accepted, %zu false, "
      "recall "
      "%.2f; %zu removed by the graph, %zu optimisations; ATE %.2f m (odometry %.2f m), KITTI %.2f %% "
      "(odometry %.2f %%)\n",
      run.trajectory.size(), run.map.keyframes.size(), run.map.points.size(), run.stats.loop_candidates,
      run.stats.loops_accepted, le.false_accepted, le.recall, run.stats.loops_rejected_by_graph,
      run.stats.graph_optimisations, slam.ate.trans_m.rmse, odo.ate.trans_m.rmse, slam.kitti.t_err_percent,
      odo.kitti.t_err_percent);
  EXPECT_EQ(run.trajectory.size(), sim_->numScans());
  EXPECT_EQ(le.false_in_graph, 0u);
  EXPECT_GE(le.keyframes_with_true_loop, 20u);
  EXPECT_GE(le.recall, 0.2);
  EXPECT_LT(slam.ate.trans_m.rmse, 0.7 * odo.ate.trans_m.rmse);
  EXPECT_LT(slam.ate.trans_m.rmse, 3.0);

  // The map agrees with the trajectory: keyframe poses are the trajectory at their stamps, map
  // points are seen by >= 3 keyframes, edges connect existing keyframes.
  std::size_t k = 0;
  for (const auto& kf : run.map.keyframes) {
    while (k < run.trajectory.size() && run.trajectory[k].stamp < kf.stamp_ns) ++k;
    ASSERT_LT(k, run.trajectory.size());
    ASSERT_EQ(run.trajectory[k].stamp, kf.stamp_ns);
    EXPECT_NEAR(run.trajectory[k].pose.x, kf.pose.x, 1e-9);
    EXPECT_FALSE(kf.points.empty());
    EXPECT_FALSE(kf.descriptor.empty());
  }
  EXPECT_GT(run.map.points.size(), 100u);
  for (const auto& p : run.map.points) EXPECT_GE(p.observed_by.size(), 3u);
  for (const auto& e : run.map.edges) {
    EXPECT_LT(e.from, run.map.keyframes.size());
    EXPECT_LT(e.to, run.map.keyframes.size());
  }
}

TEST_F(SlamOnSimulation, OneThreadIsDeterministicAndThreadsAgree) {
  const std::size_t n = std::min<std::size_t>(sim_->numScans(), 250);
  const SlamRun a = runSlam(*sim_, n, 1), b = runSlam(*sim_, n, 1);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    EXPECT_EQ(a.trajectory[i].pose.x, b.trajectory[i].pose.x) << i;
    EXPECT_EQ(a.trajectory[i].pose.phi, b.trajectory[i].pose.phi) << i;
  }
  EXPECT_EQ(a.loops.size(), b.loops.size());
  // Threads change the timing of local BA and loop corrections, not the outcome's quality.
  const SlamRun t = runSlam(*sim_, n, 3);
  ASSERT_EQ(t.trajectory.size(), n);
  const Trajectory truth(truth_->begin(), truth_->begin() + static_cast<long>(n));
  const double ate1 = eval::evaluate(a.trajectory, truth).ate.trans_m.rmse;
  const double ate3 = eval::evaluate(t.trajectory, truth).ate.trans_m.rmse;
  EXPECT_LT(ate3, ate1 + 1.0);
}

}  // namespace
}  // namespace radarslam
