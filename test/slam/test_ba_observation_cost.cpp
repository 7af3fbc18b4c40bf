// The local BA's observation residual (slam/ba_observation_cost.h): its value is the map point seen
// from the keyframe minus the measurement, over sigma, and its analytic Jacobians agree with
// Ceres' finite differences at random poses and points; with an information shape (a wall point:
// point to line) its squared norm is the shape's quadratic form, and its Jacobians still agree.
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ba_observation_cost.h"

namespace radarslam::slam_detail {
namespace {

TEST(BAObservationCost, ResidualIsThePointInTheKeyframeFrameMinusTheMeasurement) {
  const ObservationCost cost(Eigen::Vector2d(1.0, -2.0), 0.5);
  const double pose[3] = {10.0, 5.0, M_PI / 2};  // x axis of the keyframe points north
  const double point[2] = {13.0, 9.0};           // 4 m ahead, 3 m to the right
  const double* params[2] = {pose, point};
  double r[2];
  ASSERT_TRUE(cost.Evaluate(params, r, nullptr));
  EXPECT_NEAR(r[0], (4.0 - 1.0) / 0.5, 1e-12);
  EXPECT_NEAR(r[1], (-3.0 + 2.0) / 0.5, 1e-12);
}

/// 50 random observations (each with a random information shape when `shaped`) at random poses and
/// points: the analytic Jacobians against finite differences, and |r|^2 = e^T shape e.
void expectJacobiansAndNorm(unsigned seed, bool shaped) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(-80, 80), phi(-M_PI, M_PI), unit(0, 1);
  const ceres::NumericDiffOptions numeric;
  for (int i = 0; i < 50; ++i) {
    Eigen::Matrix2d shape = Eigen::Matrix2d::Identity();
    if (shaped) {
      const double a = phi(rng), ratio = unit(rng);
      const Eigen::Vector2d n(std::cos(a), std::sin(a)), t(-n.y(), n.x());
      shape = n * n.transpose() + ratio * t * t.transpose();
    }
    const ObservationCost cost(Eigen::Vector2d(xy(rng), xy(rng)), 0.05, shape);
    const ceres::GradientChecker checker(
        &cost, static_cast<const std::vector<const ceres::Manifold*>*>(nullptr), numeric);
    const double pose[3] = {xy(rng), xy(rng), phi(rng)};
    const double point[2] = {xy(rng), xy(rng)};
    const double* params[2] = {pose, point};
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(params, 1e-6, &results)) << results.error_log;
    double r[2];
    ASSERT_TRUE(cost.Evaluate(params, r, nullptr));
    const double c = std::cos(pose[2]), s = std::sin(pose[2]);
    const Eigen::Vector2d d(point[0] - pose[0], point[1] - pose[1]);
    const Eigen::Vector2d e =
        (Eigen::Vector2d(c * d.x() + s * d.y(), -s * d.x() + c * d.y()) - cost.z()) / 0.05;
    EXPECT_NEAR(r[0] * r[0] + r[1] * r[1], e.dot(shape * e), 1e-6 * (1 + e.squaredNorm()));
  }
}

TEST(BAObservationCost, AnalyticJacobiansMatchFiniteDifferences) { expectJacobiansAndNorm(7, false); }

TEST(BAObservationCost, ShapedAnalyticJacobiansMatchFiniteDifferences) { expectJacobiansAndNorm(11, true); }

TEST(BAObservationCost, AShapedObservationCountsAcrossItsLineOnly) {
  // A wall point: known along the keyframe's y (across the wall), not along x (along it).
  const Eigen::Matrix2d line = Eigen::Vector2d(0.0, 1.0).asDiagonal();
  const ObservationCost cost(Eigen::Vector2d(1.0, -2.0), 0.5, line);
  const double pose[3] = {10.0, 5.0, M_PI / 2};
  const double point[2] = {13.0, 9.0};  // (4, -3) in the keyframe's frame: 3 m along, 1 m across
  const double* params[2] = {pose, point};
  double r[2];
  ASSERT_TRUE(cost.Evaluate(params, r, nullptr));
  EXPECT_NEAR(r[0] * r[0] + r[1] * r[1], std::pow((-3.0 + 2.0) / 0.5, 2), 1e-12);
}

}  // namespace
}  // namespace radarslam::slam_detail
