// The KITTI odometry metric against hand-computed cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radarslam/eval/kitti_metric.h"
#include "synthetic.h"

using namespace radarslam;
using namespace radarslam::eval;
using mrpt::math::TPose2D;
using test::posesOf;

namespace {
// Samples 1 m + 1 nm apart: every segment then ends (to 1e-9) exactly at its nominal length. With an
// exact 1 m spacing the devkit's strict "dist > start + L" moves the end one sample further (below).
constexpr double kSpacing = 1.0 + 1e-9;
constexpr std::size_t kPoses = 1000;  // 999 m

std::size_t expectedSegments(double length, std::size_t last_index, unsigned step) {
  // Starts 0, step, 2 step, ... with start + L <= last_index (all of them reach a last frame).
  const auto max_first = static_cast<std::size_t>(static_cast<double>(last_index) - length);
  return max_first / step + 1;
}
}  // namespace

TEST(KittiMetric, IdenticalTrajectoriesScoreZero) {
  const auto gt = posesOf(test::windingDrive(800));
  const KittiResult r = computeKittiMetric(gt, gt);
  ASSERT_TRUE(r.valid());
  EXPECT_GT(r.segments, 100u);
  EXPECT_EQ(r.t_err_percent, 0.0);
  EXPECT_EQ(r.r_err_deg_per_m, 0.0);
}

TEST(KittiMetric, OnePercentScaleErrorScoresOnePercent) {
  const Trajectory gt = test::straightLine(kPoses, kSpacing);
  const KittiResult r = computeKittiMetric(posesOf(gt), posesOf(test::scaled(gt, 1.01)));
  EXPECT_NEAR(r.t_err_percent, 1.0, 1e-6);
  EXPECT_NEAR(r.r_err_deg_per_m, 0.0, 1e-12);
  std::size_t total = 0;
  for (const auto& l : r.per_length) {
    EXPECT_NEAR(l.t_err_percent, 1.0, 1e-6) << l.length_m;
    EXPECT_EQ(l.segments, expectedSegments(l.length_m, kPoses - 1, 4)) << l.length_m;
    total += l.segments;
  }
  EXPECT_EQ(r.segments, total);
  for (const auto& s : r.segment_errors) EXPECT_EQ(s.last - s.first, static_cast<std::size_t>(s.length_m));
}

TEST(KittiMetric, DividesByTheNominalLengthLikeTheDevkit) {
  // Exactly 1 m apart: the first frame with dist > start + L is start + L + 1, so a 1 % scale error
  // scores 1 % * (L + 1) / L for segments of length L (the devkit's behaviour, kept on purpose).
  const Trajectory gt = test::straightLine(kPoses, 1.0);
  const KittiResult r = computeKittiMetric(posesOf(gt), posesOf(test::scaled(gt, 1.01)));
  for (const auto& l : r.per_length)
    EXPECT_NEAR(l.t_err_percent, (l.length_m + 1) / l.length_m, 1e-9) << l.length_m;
  for (const auto& s : r.segment_errors)
    EXPECT_EQ(s.last - s.first, static_cast<std::size_t>(s.length_m) + 1);
}

TEST(KittiMetric, ConstantYawDriftGivesTheKnownDegreesPerMetre) {
  const double drift = 1e-4;  // rad per 1 m step
  const Trajectory gt = test::straightLine(kPoses, kSpacing);
  const Trajectory est = test::chain(kPoses, [&](std::size_t) { return TPose2D(kSpacing, 0, drift); });
  const KittiResult r = computeKittiMetric(posesOf(gt), posesOf(est));
  // Each segment spans L steps of `drift` over L metres (nominal): drift rad/m = 0.00573 deg/m.
  const double expected_deg_per_m = drift * 180.0 / std::numbers::pi;
  EXPECT_NEAR(r.r_err_deg_per_m, expected_deg_per_m, 1e-9);
  EXPECT_NEAR(r.r_err_deg_per_100m, 100 * expected_deg_per_m, 1e-7);
  for (const auto& l : r.per_length) EXPECT_NEAR(l.r_err_deg_per_100m, 100 * expected_deg_per_m, 1e-7);
  EXPECT_GT(r.t_err_percent, 0.0);  // the drifting heading bends the estimated path as well
}

TEST(KittiMetric, DoesNotDependOnTheEstimatesWorldFrame) {
  const Trajectory gt = test::windingDrive(900);
  const Trajectory est = test::transformed(gt, TPose2D(6.2e5, 4.85e6, 2.0));  // UTM-sized offset
  const KittiResult r = computeKittiMetric(posesOf(gt), posesOf(est));
  ASSERT_TRUE(r.valid());
  EXPECT_LT(r.t_err_percent, 1e-7);
  EXPECT_LT(r.r_err_deg_per_m, 1e-9);
}

TEST(KittiMetric, StepControlsTheSegmentStarts) {
  const Trajectory gt = test::straightLine(kPoses, kSpacing);
  const auto p = posesOf(gt);
  KittiParams params;
  params.step_frames = 1;
  params.lengths_m = {100};
  const KittiResult r = computeKittiMetric(p, p, params);
  EXPECT_EQ(r.segments, expectedSegments(100, kPoses - 1, 1));
  params.step_frames = 10;
  EXPECT_EQ(computeKittiMetric(p, p, params).segments, expectedSegments(100, kPoses - 1, 10));
}

TEST(KittiMetric, PathShorterThanTheShortestSegmentHasNoScore) {
  const Trajectory gt = test::straightLine(50, 1.0);
  const KittiResult r = computeKittiMetric(posesOf(gt), posesOf(gt));
  EXPECT_FALSE(r.valid());
  EXPECT_TRUE(std::isnan(r.t_err_percent));
  EXPECT_TRUE(std::isnan(r.r_err_deg_per_100m));
  ASSERT_EQ(r.per_length.size(), 8u);
  EXPECT_EQ(r.per_length[0].segments, 0u);
}

TEST(KittiMetric, RejectsMismatchedInputs) {
  const auto p = posesOf(test::straightLine(10, 1.0));
  EXPECT_THROW(computeKittiMetric(p, {p.begin(), p.end() - 1}), std::invalid_argument);
  KittiParams zero_step;
  zero_step.step_frames = 0;
  EXPECT_THROW(computeKittiMetric(p, p, zero_step), std::invalid_argument);
}

TEST(KittiMetric, CumulativeDistancesFollowThePath) {
  const auto d = cumulativeDistances({TPose2D(0, 0, 0), TPose2D(3, 4, 0), TPose2D(3, 10, 1)});
  ASSERT_EQ(d.size(), 3u);
  EXPECT_DOUBLE_EQ(d[1], 5.0);
  EXPECT_DOUBLE_EQ(d[2], 11.0);
}
