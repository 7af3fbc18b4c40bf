#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radarslam/core/errors.h"
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

TEST(TrajectoryPlausibility, RefusesNonFiniteAndFarPoses) {
  Trajectory t{{1, TPose2D(0, 0, 0)}, {2, TPose2D(1e6, -9.9e6, 0.1)}};
  EXPECT_FALSE(firstImplausiblePose(t));
  EXPECT_NO_THROW(checkPlausiblePoses(t, "gt.csv"));
  for (double bad : {1e308, -2e7, std::nan(""), HUGE_VAL}) {
    Trajectory u = t;
    u.push_back({3, TPose2D(bad, 0, 0)});
    EXPECT_EQ(firstImplausiblePose(u), 2u);
    EXPECT_THROW(checkPlausiblePoses(u, "gt.csv"), InputError);
  }
}
