#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radarslam/frontend/motion_compensation.h"

namespace radarslam {
namespace {

TEST(FrontendMotionCompensation, TwistFromDeltaInvertsIntegration) {
  const BodyVelocity v{9.0, -0.4, 0.35};
  const double dt = 0.25;
  const auto delta = twistToPose(v, dt);
  const BodyVelocity back = twistFromDelta(delta, dt);
  EXPECT_NEAR(back.vx, v.vx, 1e-9);
  EXPECT_NEAR(back.vy, v.vy, 1e-9);
  EXPECT_NEAR(back.omega, v.omega, 1e-9);
  const BodyVelocity straight = twistFromDelta({2.0, 0.0, 0.0}, 0.5);
  EXPECT_NEAR(straight.vx, 4.0, 1e-12);
  EXPECT_NEAR(straight.omega, 0.0, 1e-12);
}

TEST(FrontendMotionCompensation, CompensationMovesALaterReturnForward) {
  // Driving forward at 10 m/s: a wall point 20 m to the left seen 0.1 s after the reference time
  // was measured from 1 m further on, so in the reference frame it is 1 m further forward.
  const BodyVelocity v{10.0, 0.0, 0.0};
  const Eigen::Vector2d p = compensatePoint({5.0, 20.0}, 0.1, v);
  EXPECT_NEAR(p.x(), 6.0, 1e-12);
  EXPECT_NEAR(p.y(), 20.0, 1e-12);
  const Eigen::Vector2d q =
      decompensatePoint(compensatePoint({-3.0, 7.0}, -0.08, {5, 1, 0.4}), -0.08, {5, 1, 0.4});
  EXPECT_NEAR(q.x(), -3.0, 1e-12);
  EXPECT_NEAR(q.y(), 7.0, 1e-12);
}

TEST(FrontendMotionCompensation, AzimuthClockGivesFiringTimeOfADirection) {
  CObservationRadarScan scan;
  scan.resize(400, 10);
  const StampNs t0 = 1'000'000'000'000;
  for (int i = 0; i < 400; ++i) scan.azimuth_stamps_ns[i] = t0 + i * 625'000;  // 250 ms sweep
  const AzimuthClock clock(scan);
  const double ref_offset = 399 * 625e-6 / 2;  // reference = mid-sweep
  EXPECT_NEAR(clock.offsetSeconds(0.0), -ref_offset, 1e-9);
  EXPECT_NEAR(clock.offsetSeconds(std::numbers::pi), 200 * 625e-6 - ref_offset, 1e-9);
  EXPECT_NEAR(clock.offsetSeconds(-0.5 * std::numbers::pi), 300 * 625e-6 - ref_offset, 1e-9);
  EXPECT_NEAR(clock.offsetSeconds(2 * std::numbers::pi - 1e-4), -ref_offset, 1e-9);  // wraps to azimuth 0
  EXPECT_EQ(AzimuthClock().offsetSeconds(1.0), 0.0);
}

}  // namespace
}  // namespace radarslam
