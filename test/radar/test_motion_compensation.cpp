// Motion compensation: the SE(2) exponential, identity at rest, pure translation, and undoing a
// simulated distortion exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <radarslam/core/errors.h>
#include <radarslam/radar/motion_compensation.h>

#include "synthetic_scan.h"

namespace radarslam {
namespace {

using test::makeScan;

std::vector<RadarPoint> somePoints(const CObservationRadarScan& scan, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-80.f, 80.f);
  std::vector<RadarPoint> pts(n);
  for (auto& p : pts) {
    p.x = coord(rng);
    p.y = coord(rng);
    p.range_m = std::hypot(p.x, p.y);
    p.power = 100;
    p.azimuth = rng() % scan.num_azimuths;
  }
  return pts;
}

TEST(MotionCompensation, TwistExponentialIsAOneParameterGroup) {
  const BodyVelocity v{9.0, -0.4, 0.35};
  const RigidTransform2D a = integrateTwist(v, 0.07), b = integrateTwist(v, 0.05),
                         ab = integrateTwist(v, 0.12);
  double x, y;  // compose a then b: translation a.t + R(a) b.t
  a.apply(b.x, b.y, x, y);
  EXPECT_NEAR(x, ab.x, 1e-12);
  EXPECT_NEAR(y, ab.y, 1e-12);
  EXPECT_NEAR(a.theta + b.theta, ab.theta, 1e-12);
  // A quarter circle of radius 10 m: vx = 10 m/s, omega = pi/2 rad/s for 1 s ends at (10, 10).
  const RigidTransform2D q = integrateTwist({10.0, 0.0, std::numbers::pi / 2}, 1.0);
  const double radius = 10.0 / (std::numbers::pi / 2);
  EXPECT_NEAR(q.x, radius, 1e-12);
  EXPECT_NEAR(q.y, radius, 1e-12);
  // The small-angle series joins the closed form continuously.
  const RigidTransform2D s1 = integrateTwist({5.0, 1.0, 0.999e-9}, 1.0),
                         s2 = integrateTwist({5.0, 1.0, 1.001e-9}, 1.0);
  EXPECT_NEAR(s1.x, s2.x, 1e-11);
  EXPECT_NEAR(s1.y, s2.y, 1e-11);
  EXPECT_NEAR(s2.y, 1.0 + 5.0 * 1e-9 / 2, 1e-11);  // first order: u_y + w u_x / 2
}

TEST(MotionCompensation, ZeroVelocityIsIdentity) {
  const auto scan = makeScan(400, 100);
  const auto pts = somePoints(scan, 200, 1);
  const auto out = motionCompensated(pts, scan, BodyVelocity{});
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(out[i].x, pts[i].x);
    EXPECT_EQ(out[i].y, pts[i].y);
    EXPECT_EQ(out[i].azimuth, pts[i].azimuth);
  }
}

TEST(MotionCompensation, PureTranslationMovesByVelocityTimesTime) {
  const auto scan = makeScan(400, 100);
  const auto pts = somePoints(scan, 200, 2);
  const BodyVelocity v{10.0, -2.0, 0.0};
  const auto out = motionCompensated(pts, scan, v);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double dt = toSeconds(scan.azimuth_stamps_ns[pts[i].azimuth] - scan.refStampNs());
    EXPECT_NEAR(out[i].x, pts[i].x + 10.0 * dt, 1e-5);
    EXPECT_NEAR(out[i].y, pts[i].y - 2.0 * dt, 1e-5);
    EXPECT_NEAR(out[i].range_m, std::hypot(out[i].x, out[i].y), 1e-4);
  }
  // The first azimuth is fired 399 * 625 us / 2 = 124.6875 ms before the reference time.
  std::vector<RadarPoint> first(1);
  first[0].x = 20.f;
  compensateMotion(first, scan, v);
  EXPECT_NEAR(first[0].x, 20.0 - 10.0 * 0.1246875, 1e-5);
}

TEST(MotionCompensation, UndoesASimulatedDistortion) {
  // Static world points seen by a sensor moving on an arc; each is measured in the sensor frame
  // at its azimuth's firing time. Compensation must return them to the reference frame.
  const auto scan = makeScan(400, 100);
  const BodyVelocity v{12.0, 0.5, 0.6};
  auto world = somePoints(scan, 500, 3);  // in the reference frame
  std::vector<RadarPoint> measured = world;
  for (RadarPoint& p : measured) {
    const double dt = toSeconds(scan.azimuth_stamps_ns[p.azimuth] - scan.refStampNs());
    const RigidTransform2D t = integrateTwist(v, dt);  // sensor at firing time, in the reference frame
    // p_sensor = R^T (p_ref - t)
    const double dx = p.x - t.x, dy = p.y - t.y, c = std::cos(t.theta), s = std::sin(t.theta);
    p.x = static_cast<float>(c * dx + s * dy);
    p.y = static_cast<float>(-s * dx + c * dy);
  }
  double max_distortion = 0;
  for (std::size_t i = 0; i < world.size(); ++i)
    max_distortion =
        std::max(max_distortion, double(std::hypot(measured[i].x - world[i].x, measured[i].y - world[i].y)));
  EXPECT_GT(max_distortion, 1.0);  // the distortion is large before compensation
  compensateMotion(measured, scan, v);
  for (std::size_t i = 0; i < world.size(); ++i) {
    EXPECT_NEAR(measured[i].x, world[i].x, 1e-4);
    EXPECT_NEAR(measured[i].y, world[i].y, 1e-4);
  }
}

TEST(MotionCompensation, RejectsPointsOfOtherScans) {
  const auto scan = makeScan(10, 10);
  std::vector<RadarPoint> pts(1);
  pts[0].azimuth = 10;
  EXPECT_THROW(compensateMotion(pts, scan, {1, 0, 0}), InputError);
}

}  // namespace
}  // namespace radarslam
