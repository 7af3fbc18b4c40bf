#include <gtest/gtest.h>

#include <cmath>

#include "radarslam/frontend/motion_prior_bound.h"

namespace radarslam {
namespace {

TEST(MotionPriorBound, FixedRadiusUntilEnoughSamples) {
  MatchParams p;
  p.radius_m = 4.0;
  p.adaptive_min_samples = 3;
  MotionPriorBound b(p, 0.25, 12.5);
  b.addDeviation({1, 0, 0}, {1.1, 0, 0});
  b.addDeviation({1, 0, 0}, {1.1, 0, 0});
  const SearchRadius r = b.radius();
  EXPECT_DOUBLE_EQ(r.at(0), 4.0);
  EXPECT_DOUBLE_EQ(r.at(80), 4.0);
}

TEST(MotionPriorBound, RadiusIsKSigmaOfTheRunningDeviation) {
  MatchParams p;
  p.adaptive_min_samples = 2;
  p.radius_sigmas = 3.0;
  const double kp = 0.25;
  MotionPriorBound b(p, kp, 12.5);
  // Deviations of 0.3 m and 0.4 m in translation, 0.01 and 0.02 rad in heading.
  b.addDeviation({2, 0, 0}, {2.3, 0, 0});
  b.addDeviation({2, 0, 0.1}, {2, 0, 0.1});
  b.addDeviation({0, 0, 0}, {0, 0.4, 0.01});
  b.addDeviation({0, 0, 0}, {0, 0, -0.02});
  EXPECT_NEAR(b.sigmaTranslation(), std::sqrt((0.09 + 0.16) / 4), 1e-12);
  EXPECT_NEAR(b.sigmaRotation(), std::sqrt((1e-4 + 4e-4) / 4), 1e-12);
  const SearchRadius r = b.radius();
  const double st2 = 0.25 / 4, sp = std::sqrt(5e-4 / 4);
  EXPECT_NEAR(r.at(0), 3.0 * std::sqrt(st2 + 2 * kp * kp), 1e-12);
  EXPECT_NEAR(r.at(50), 3.0 * std::sqrt(st2 + 2 * kp * kp + 2500 * sp * sp), 1e-12);
}

TEST(MotionPriorBound, DeviationIsMeasuredInThePredictedFrame) {
  // Predicted 90 degrees to the left and 1 m ahead; the estimate is 1 m further along the
  // predicted heading: a pure 1 m deviation, no rotation.
  MatchParams p;
  p.adaptive_min_samples = 1;
  MotionPriorBound b(p, 0.0, 100);
  b.addDeviation({1, 0, M_PI / 2}, {1, 1, M_PI / 2});
  EXPECT_NEAR(b.sigmaTranslation(), 1.0, 1e-12);
  EXPECT_NEAR(b.sigmaRotation(), 0.0, 1e-12);
}

TEST(MotionPriorBound, StaleVelocityWidensTheBoundAndTheCapHolds) {
  MatchParams p;
  p.adaptive_min_samples = 1;
  MotionPriorBound b(p, 0.0, 5.0);
  b.addDeviation({1, 0, 0}, {1.5, 0, 0.01});
  const SearchRadius fresh = b.radius(0), stale = b.radius(3);
  EXPECT_NEAR(stale.at(0), 2.0 * fresh.at(0), 1e-12);  // sqrt(1 + 3) = 2
  EXPECT_NEAR(stale.per_range, 2.0 * fresh.per_range, 1e-12);
  EXPECT_DOUBLE_EQ(b.radius(1000).at(100), 5.0);
}

TEST(MotionPriorBound, OffMeansTheFixedRadius) {
  MatchParams p;
  p.adaptive_radius = false;
  p.adaptive_min_samples = 1;
  MotionPriorBound b(p, 0.25, 12.5);
  b.addDeviation({1, 0, 0}, {1.1, 0, 0.05});
  EXPECT_DOUBLE_EQ(b.radius().at(80), p.radius_m);
}

TEST(MotionPriorBound, NonFiniteDeviationsAreIgnored) {
  MatchParams p;
  MotionPriorBound b(p, 0.25, 12.5);
  b.addDeviation({1, 0, 0}, {std::nan(""), 0, 0});
  EXPECT_EQ(b.samples(), 0);
}

TEST(MotionPriorBound, CovarianceIsTheSecondMomentOfTheDeviationsOnceEnoughAreKnown) {
  MatchParams p;
  p.adaptive_min_samples = 3;
  MotionPriorBound b(p, 0.25, 12.5);
  b.addDeviation({2, 0, 0}, {2.3, 0, 0.01});    // D = (0.3, 0, 0.01)
  b.addDeviation({0, 0, 0}, {0, -0.4, -0.02});  // D = (0, -0.4, -0.02)
  EXPECT_TRUE(b.covariance().isZero()) << "2 of 3 samples: no prior yet";
  b.addDeviation({1, 0, M_PI / 2}, {1, 1, M_PI / 2});  // D = (1, 0, 0) in the predicted frame
  const Eigen::Matrix3d c = b.covariance();
  EXPECT_NEAR(c(0, 0), (0.09 + 1.0) / 3, 1e-12);
  EXPECT_NEAR(c(1, 1), 0.16 / 3, 1e-12);
  EXPECT_NEAR(c(2, 2), (1e-4 + 4e-4) / 3, 1e-12);
  EXPECT_NEAR(c(0, 2), 0.003 / 3, 1e-12);
  EXPECT_NEAR(c(1, 2), 0.008 / 3, 1e-12);
  EXPECT_NEAR(c(0, 1), 0.0, 1e-12);
  EXPECT_TRUE(c.isApprox(c.transpose()));
}

}  // namespace
}  // namespace radarslam
