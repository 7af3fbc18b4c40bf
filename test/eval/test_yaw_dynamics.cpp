// yawDynamics: yaw rate and yaw acceleration percentiles of a trajectory.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "radarslam/eval/yaw_dynamics.h"

using namespace radarslam;

namespace {
/// Poses every 0.25 s turning at `rate_dps(k)` during step k.
template <typename Rate>
Trajectory turning(int steps, Rate rate_dps) {
  Trajectory t;
  double yaw = 3.0;  // starts near +-pi: the wrap must not count as a turn
  t.push_back({0, {0, 0, yaw}});
  for (int k = 0; k < steps; ++k) {
    yaw = std::remainder(yaw + rate_dps(k) * M_PI / 180 * 0.25, 2 * M_PI);
    t.push_back({static_cast<StampNs>(k + 1) * kNsPerSec / 4, {0, 0, yaw}});
  }
  return t;
}
}  // namespace

TEST(YawDynamics, AConstantTurnHasItsRateAndNoAcceleration) {
  const eval::YawDynamics d = eval::yawDynamics(turning(100, [](int) { return -12.0; }));
  EXPECT_NEAR(d.rate_p99_dps, 12.0, 1e-6);
  EXPECT_NEAR(d.rate_max_dps, 12.0, 1e-6);
  EXPECT_NEAR(d.accel_max_dps2, 0.0, 1e-6);
  EXPECT_EQ(d.samples, 99u);
}

TEST(YawDynamics, ARateStepIsAnAccelerationOverOneScanPeriod) {
  const eval::YawDynamics d = eval::yawDynamics(turning(100, [](int k) { return k < 50 ? 0.0 : 20.0; }));
  EXPECT_NEAR(d.rate_max_dps, 20.0, 1e-6);
  EXPECT_NEAR(d.accel_max_dps2, 80.0, 1e-6);  // 20 deg/s within 0.25 s
  EXPECT_NEAR(d.accel_p95_dps2, 0.0, 1e-6);   // one sample of 99
}

TEST(YawDynamics, RefusesTooFewPosesAndStampsThatDoNotIncrease) {
  EXPECT_THROW(eval::yawDynamics(turning(1, [](int) { return 1.0; })), std::invalid_argument);
  Trajectory t = turning(5, [](int) { return 1.0; });
  t[3].stamp = t[2].stamp;
  EXPECT_THROW(eval::yawDynamics(t), std::invalid_argument);
}
