// Unit tests of the integrity checks (reloc/integrity.h).
#include <gtest/gtest.h>

#include <cmath>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/reloc/integrity.h"

namespace radarslam {
namespace {

TEST(Integrity, Chi2QuantileMatchesTables) {
  EXPECT_NEAR(chi2Quantile3(0.95), 7.815, 1e-3);
  EXPECT_NEAR(chi2Quantile3(0.99), 11.345, 1e-3);
  EXPECT_NEAR(chi2Quantile3(0.999), 16.266, 1e-3);
}

TEST(Integrity, OdometryCovarianceGrowsWithDistanceAndTurn) {
  const IntegrityParams p;
  const Eigen::Matrix3d still = odometryCovariance({0, 0, 0}, p);
  const Eigen::Matrix3d moving = odometryCovariance({3, 0, 0.2}, p);
  EXPECT_NEAR(std::sqrt(still(0, 0)), p.odom_sigma_floor_m, 1e-12);
  EXPECT_NEAR(std::sqrt(moving(0, 0)), p.odom_sigma_floor_m + 3 * p.odom_sigma_per_m, 1e-12);
  EXPECT_NEAR(std::sqrt(moving(2, 2)),
              p.odom_sigma_floor_rad + 0.2 * p.odom_sigma_rad_per_rad + 3 * p.odom_sigma_rad_per_m, 1e-12);
}

TEST(Integrity, ComposeCovarianceRotatesAndAddsLeverArm) {
  // Heading uncertainty of a at 90 deg moves the end of a 10 m step sideways (along -x).
  Eigen::Matrix3d ca = Eigen::Matrix3d::Zero();
  ca(2, 2) = 0.01;
  const Eigen::Matrix3d c = composeCovariance({0, 0, M_PI / 2}, ca, {10, 0, 0}, Eigen::Matrix3d::Zero());
  EXPECT_NEAR(c(0, 0), 100 * 0.01, 1e-9);
  EXPECT_NEAR(c(1, 1), 0, 1e-9);
}

TEST(Integrity, PathCovarianceGrowsWithThePathNotWithTheKeyframeOrder) {
  // Keyframes every 10 m along x, and keyframe 5 back beside keyframe 0 (a revisit): along the path
  // 0 -> 5 the relative pose is as certain as one short step; along the keyframe order, 50 m of drive.
  KeyframeMap map;
  auto add = [&](mrpt::math::TPose2D pose) {
    Keyframe kf;
    kf.pose = pose;
    map.keyframes.push_back(kf);
  };
  for (int k = 0; k < 5; ++k) add({10.0 * k, 0, 0});
  add({0.5, 2.0, M_PI});
  const IntegrityParams p;
  const Eigen::Matrix3d direct = pathCovariance(map, {0, 5}, p);
  const Eigen::Matrix3d around = pathCovariance(map, {0, 1, 2, 3, 4, 5}, p);
  EXPECT_TRUE(pathCovariance(map, {3}, p).isZero());
  EXPECT_NEAR(direct(2, 2), odometryCovariance({0.5, 2.0, M_PI}, p)(2, 2), 1e-12);
  EXPECT_GT(position3Sigma(around), 10 * position3Sigma(direct));
  // Each step's own covariance, compounded: one step equals the noise model of that motion.
  const Eigen::Matrix3d one = pathCovariance(map, {1, 2}, p);
  EXPECT_TRUE(one.isApprox(odometryCovariance({10, 0, 0}, p), 1e-12));
}

TEST(Integrity, FusionFillsTheWeakDirection) {
  // Registration: good across a corridor along x, useless along it; prediction 1 m further along x.
  Eigen::Matrix3d reg = Eigen::Vector3d(1e6, 0.01, 1e-4).asDiagonal();
  Eigen::Matrix3d pred = Eigen::Vector3d(0.04, 0.04, 1e-4).asDiagonal();
  mrpt::math::TPose2D out;
  Eigen::Matrix3d cov;
  fusePoses({11, 0.5, 0}, pred, {10, 0, 0}, reg, out, cov);
  EXPECT_NEAR(out.x, 11, 1e-3);   // along: the prediction
  EXPECT_NEAR(out.y, 0.1, 1e-3);  // across: mostly the registration (0.04 vs 0.01)
  EXPECT_LT(cov(0, 0), 0.0401);
  EXPECT_GT(xyCondition(reg), 100);
}

TEST(Integrity, FitDropNeedsHistoryAndIsRelativeToTheMedian) {
  const IntegrityParams p;
  FitMonitor m(p);
  EXPECT_FALSE(m.drop(0.1));  // no history
  for (int i = 0; i < 30; ++i) m.add(0.85 + 0.01 * (i % 3));
  EXPECT_FALSE(m.drop(0.8));
  EXPECT_TRUE(m.drop(0.6));  // > 4 sigmas (floor 0.03) below 0.86
}

TEST(Integrity, WindowCatchesASlowWalkThatSingleStepsHide) {
  IntegrityParams p;
  MotionWindow w(p);
  const Eigen::Matrix3d reg = Eigen::Vector3d(0.01, 0.01, 1e-5).asDiagonal();
  // Odometry says 2 m forward per scan; the map poses drift 0.25 m sideways per scan.
  mrpt::math::TPose2D pose{0, 0, 0};
  double worst = 0;
  for (int k = 0; k < 11; ++k) {
    w.addMotion({2, 0, 0}, odometryCovariance({2, 0, 0}, p));
    if (k > 0) pose = {pose.x + 2, pose.y + 0.25, 0};
    worst = std::max(worst, w.test(pose, reg));
    w.addPose(true, pose, reg);
  }
  EXPECT_GT(worst, chi2Quantile3(p.chi2_probability));
  // A consistent drive passes.
  MotionWindow ok(p);
  pose = {0, 0, 0};
  for (int k = 0; k < 11; ++k) {
    ok.addMotion({2, 0, 0}, odometryCovariance({2, 0, 0}, p));
    if (k > 0) pose = {pose.x + 2, pose.y, 0};
    EXPECT_LT(ok.test(pose, reg), chi2Quantile3(0.95));
    ok.addPose(true, pose, reg);
  }
}

TEST(Integrity, BeyondTheMappedPathAPoseIsOutsideAndInheritsTheLeverUncertainty) {
  KeyframeMap map;
  for (int k = 0; k <= 50; ++k) {  // keyframes every 2 m along y = 0
    Keyframe kf;
    kf.pose = {2.0 * k, 0.0, 0.0};
    map.keyframes.push_back(kf);
  }
  const IntegrityParams p;  // max_keyframe_distance_m 10
  const MapCoverage on_street = mapCoverage(map, {51.0, 3.5, 0.2}, p);
  EXPECT_FALSE(on_street.outside);
  EXPECT_TRUE(on_street.keyframe == 25 || on_street.keyframe == 26);
  EXPECT_EQ(on_street.extra_cov, Eigen::Matrix3d::Zero());
  EXPECT_FALSE(mapCoverage(map, {109.0, 0.0, 0.0}, p).outside);  // 9 m past the last keyframe
  const MapCoverage near = mapCoverage(map, {115.0, 0.0, 0.0}, p),
                    far = mapCoverage(map, {140.0, 0.0, 0.0}, p);
  EXPECT_TRUE(near.outside);
  EXPECT_EQ(near.keyframe, 50);
  EXPECT_NEAR(near.distance_m, 15.0, 1e-9);
  EXPECT_TRUE(far.outside);
  // The uncertainty grows with the lever (the odometry noise model over the distance).
  EXPECT_GT(near.extra_cov(0, 0), 0.0);
  EXPECT_GT(far.extra_cov(0, 0), near.extra_cov(0, 0));
  EXPECT_GT(far.extra_cov(2, 2), near.extra_cov(2, 2));
  EXPECT_FALSE(mapCoverage(KeyframeMap{}, {0, 0, 0}, p).outside);
}

TEST(Integrity, YamlValidRanges) {
  IntegrityParams p;
  loadParams(YamlParams::fromText("chi2_probability: 0.99\nmax_failures: 2\n", "t.yaml"), p);
  EXPECT_DOUBLE_EQ(p.chi2_probability, 0.99);
  EXPECT_EQ(p.max_failures, 2);
  EXPECT_THROW(loadParams(YamlParams::fromText("chi2_probability: 1.5\n", "t.yaml"), p), InputError);
  EXPECT_THROW(loadParams(YamlParams::fromText("window_scans: 1\n", "t.yaml"), p), InputError);
  IntegrityParams q;
  loadParams(YamlParams::fromText("max_keyframe_distance_m: 25\n", "t.yaml"), q);
  EXPECT_DOUBLE_EQ(q.max_keyframe_distance_m, 25.0);
  EXPECT_THROW(loadParams(YamlParams::fromText("max_keyframe_distance_m: 0\n", "t.yaml"), q), InputError);
}

}  // namespace
}  // namespace radarslam
