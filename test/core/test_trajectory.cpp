#include <gtest/gtest.h>

#include <numbers>

#include "radarslam/core/trajectory.h"

using namespace radarslam;
using mrpt::math::TPose2D;

TEST(Trajectory, InterpolatesLinearlyAndAcrossTheAngleWrap) {
  const double pi = std::numbers::pi;
  Trajectory t{{0, TPose2D(0, 0, pi - 0.1)}, {100, TPose2D(10, -2, -pi + 0.1)}};
  const auto mid = interpolatePose(t, 50);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->x, 5.0, 1e-12);
  EXPECT_NEAR(mid->y, -1.0, 1e-12);
  EXPECT_NEAR(std::abs(mid->phi), pi, 1e-9);  // through pi, not through 0
  EXPECT_FALSE(interpolatePose(t, 101));
  EXPECT_FALSE(interpolatePose(t, 50, /*max_gap_ns=*/99));
  EXPECT_NEAR(pathLength(t), std::hypot(10.0, 2.0), 1e-12);
}

TEST(Trajectory, DetectsNonIncreasingStamps) {
  Trajectory t{{0, {}}, {5, {}}, {5, {}}};
  ASSERT_TRUE(firstNonIncreasingStamp(t));
  EXPECT_EQ(*firstNonIncreasingStamp(t), 2u);
}
