// rotateCovariance: the (x, y) block turns with the frame, the heading variance does not.
#include <gtest/gtest.h>

#include <cmath>

#include "radarslam/core/se2_covariance.h"

namespace radarslam {
namespace {

TEST(Se2Covariance, AQuarterTurnSwapsTheAxes) {
  Eigen::Matrix3d cov = Eigen::Vector3d(4.0, 1.0, 0.1).asDiagonal();
  const Eigen::Matrix3d r = rotateCovariance(cov, M_PI / 2);
  EXPECT_NEAR(r(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(r(1, 1), 4.0, 1e-12);
  EXPECT_NEAR(r(2, 2), 0.1, 1e-12);
  EXPECT_NEAR(r(0, 1), 0.0, 1e-12);
}

TEST(Se2Covariance, RotationMatchesComposingFromAPoseAtTheOriginWithoutUncertainty) {
  Eigen::Matrix3d cov;
  cov << 2.0, 0.3, 0.05, 0.3, 0.5, -0.02, 0.05, -0.02, 0.01;
  for (const double a : {-2.5, -0.4, 0.0, 0.7, 3.0}) {
    const Eigen::Matrix3d via_compose = composeCovariance({0, 0, a}, Eigen::Matrix3d::Zero(), {0, 0, 0}, cov);
    EXPECT_TRUE(rotateCovariance(cov, a).isApprox(via_compose, 1e-12)) << a;
    EXPECT_TRUE(rotateCovariance(rotateCovariance(cov, a), -a).isApprox(cov, 1e-12)) << a;
  }
}

}  // namespace
}  // namespace radarslam
