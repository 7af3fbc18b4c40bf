// Unit tests of reloc/fix_hypotheses.h: places the verifier refused as ambiguous, told apart (or
// not) by the map around each alignment, in one scan or along the drive.
#include <gtest/gtest.h>

#include <cmath>

#include "radarslam/reloc/fix_hypotheses.h"
#include "radarslam/reloc/integrity.h"

namespace radarslam {
namespace {

// A street along x with walls at y = +-6 m and a post every 12 m: a view of it fits as well shifted
// by a period. Optionally a 10 x 35 m building north of the street at x = building_x .. +10 m,
// y 10..45 m, with a wall every 2.5 m inside (a multi-storey car park seen through its sides). The map holds
// keyframes every 30 m along the street, each with the points within 15 m of it along x.
struct Street {
  std::vector<Eigen::Vector2d> world;
  KeyframeMap map;
};

Street street(std::optional<double> building_x) {
  Street s;
  auto& w = s.world;
  for (double x = -120; x <= 180; x += 0.25) w.emplace_back(x, 6.0), w.emplace_back(x, -6.0);
  for (double x = -120; x <= 180; x += 12.0)
    for (double d = -0.3; d <= 0.31; d += 0.3) w.emplace_back(x + d, 3.0), w.emplace_back(x, 3.0 + d);
  if (building_x) {  // narrower than a period: shifted by one it overlaps nothing
    const double b = *building_x;
    for (double y = 10; y <= 45; y += 2.5)
      for (double t = 0; t < 10; t += 0.25) w.emplace_back(b + t, y);
    for (double t = 0; t < 35; t += 0.25) w.emplace_back(b, 10 + t), w.emplace_back(b + 10, 10 + t);
  }
  for (int k = 0; k < 10; ++k) {
    Keyframe kf;
    kf.id = k;
    kf.pose = {-105.0 + 30.0 * k, 0.0, 0.0};
    for (const auto& q : w)
      if (q.x() - kf.pose.x >= -15 && q.x() - kf.pose.x < 15)  // each world point in one keyframe
        kf.points.push_back({static_cast<float>(q.x() - kf.pose.x), static_cast<float>(q.y()), 1.f});
    s.map.keyframes.push_back(std::move(kf));
  }
  return s;
}

/// The scan of a sensor at (x, 0) heading along the street: every point within `range` m.
std::vector<RadarPoint> scanAt(const Street& s, double x, double range = 50) {
  std::vector<RadarPoint> scan;
  for (const auto& q : s.world) {
    const Eigen::Vector2d r(q.x() - x, q.y());
    if (r.norm() > range) continue;
    RadarPoint p;
    p.x = static_cast<float>(r.x());
    p.y = static_cast<float>(r.y() + 0.02 * std::sin(7 * q.x()));
    p.range_m = static_cast<float>(r.norm());
    scan.push_back(p);
  }
  return scan;
}

MapTrackerParams params() {
  MapTrackerParams p;
  p.submap.max_path_m = 0;  // every keyframe near: no second copy
  return p;
}

const double kChi2 = chi2Quantile3(0.99);

// The verifier's view of the scan at (x, 0): its alignment 12 m off (on the next post) and the
// true one and two more periods as rivals.
std::vector<ContestedPlace> contested(double x = 0) {
  return {ContestedPlace{
      0, {{x + 12.1, 0.2, 0.01}, {x + 0.1, -0.2, 0.0}, {x - 23.9, 0.1, 0.0}, {x - 11.8, 0.0, 0.0}}}};
}

/// The hypotheses of the scan at the origin of street(building_x), seeded from contested().
struct SeededAtTheOrigin {
  Street s;
  MapTracker tracker;
  FixHypotheses h;
  explicit SeededAtTheOrigin(std::optional<double> building_x)
      : s(street(building_x)), tracker(s.map, params()), h(tracker, s.map, kChi2) {
    h.seed(scanAt(s, 0), contested());
  }
};

Eigen::Matrix3d odometryNoise() { return Eigen::Vector3d(0.05, 0.05, 1e-4).asDiagonal(); }

TEST(FixHypotheses, TheMapAroundTheAlignmentsTellsThemApartInOneScan) {
  const Street s = street(20.0);  // 20..30 m: in view of the origin
  MapTracker tracker(s.map, params());
  FixHypotheses h(tracker, s.map, kChi2);
  h.seed(scanAt(s, 0), contested());
  EXPECT_EQ(h.registrations(), 4u);
  ASSERT_EQ(h.size(), 1u) << "the building rules the shifted alignments out";
  const TrackResult& r = h.hypotheses().front().last;
  EXPECT_LT(std::hypot(r.icp.pose.x, r.icp.pose.y), 0.2) << "the true alignment, not the verifier's";
  EXPECT_EQ(h.unique(1), &h.hypotheses().front());
  EXPECT_EQ(h.unique(2), nullptr) << "registered in one scan only";
}

TEST(FixHypotheses, AStreetThatRepeatsStaysAmbiguous) {
  const Street s = street(std::nullopt);
  MapTracker tracker(s.map, params());
  FixHypotheses h(tracker, s.map, kChi2);
  // 40 m scans: shifted by a period they stay within the submap (keyframes within 60 m, clouds
  // +-15 m of them), which would otherwise rule the shifted alignments out by the points it lacks.
  h.seed(scanAt(s, 0, 40), contested());
  for (double x = 10; x <= 30; x += 10) h.advance(scanAt(s, x, 40), {10.0, 0.0, 0.0}, odometryNoise());
  EXPECT_GE(h.size(), 2u) << "every period fits as well all along the street";
  EXPECT_EQ(h.unique(1), nullptr);
}

TEST(FixHypotheses, TheDriveTellsThemApartWhenTheBuildingComesIntoView) {
  const Street s = street(62.0);  // beyond the 50 m range from the origin, in view from x = 20
  MapTracker tracker(s.map, params());
  FixHypotheses h(tracker, s.map, kChi2);
  h.seed(scanAt(s, 0), contested());
  ASSERT_GE(h.size(), 2u) << "nothing tells the periods apart at the origin";
  double x = 0;
  while (h.size() > 1 && x < 40) {
    x += 10;
    h.advance(scanAt(s, x), {10.0, 0.0, 0.0}, odometryNoise());
    h.support(contested(x));  // the global search of this scan
  }
  ASSERT_NE(h.unique(2), nullptr) << "still " << h.size() << " hypotheses at x = " << x;
  const auto& pose = h.unique(2)->last.icp.pose;
  EXPECT_NEAR(pose.x, x, 0.2);
  EXPECT_NEAR(pose.y, 0, 0.2);
  EXPECT_LE(x, 30) << "the building is in view from x = 20";
}

TEST(FixHypotheses, TheLastOneLeftIsAFixOnlyWhenTheSearchPointedAtItAgain) {
  // The right place may never have been seeded: surviving its rivals is not enough, the global
  // search of confirm_fixes scans must have pointed at it.
  SeededAtTheOrigin seeded(20.0);
  const Street& s = seeded.s;
  FixHypotheses& h = seeded.h;
  ASSERT_EQ(h.size(), 1u);
  h.advance(scanAt(s, 10), {10.0, 0.0, 0.0}, odometryNoise());
  h.support({ContestedPlace{1, {{-40.0, 0.0, 0.0}, {10.0, 0.0, 0.5}}}});  // elsewhere, or turned
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h.hypotheses().front().support, 1);
  EXPECT_EQ(h.unique(2), nullptr) << "registered twice, pointed at once";
  h.advance(scanAt(s, 20), {10.0, 0.0, 0.0}, odometryNoise());
  h.support(contested(20));
  ASSERT_NE(h.unique(2), nullptr);
  EXPECT_NEAR(h.unique(2)->last.icp.pose.x, 20, 0.2);
}

TEST(FixHypotheses, AMotionTheOdometryDisagreesWithIsDropped) {
  SeededAtTheOrigin seeded(20.0);
  const Street& s = seeded.s;
  FixHypotheses& h = seeded.h;
  ASSERT_EQ(h.size(), 1u);
  // The odometry says 10 m, the scan is from 12 m (a post period further): the map pulls the
  // registration 2 m from the prediction, far outside the odometry's sigma.
  h.advance(scanAt(s, 12), {10.0, 0.0, 0.0}, Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal());
  EXPECT_TRUE(h.empty());
}

TEST(FixHypotheses, StartsTheRegistrationCannotTellApartAreRegisteredOnce) {
  const Street s = street(std::nullopt);
  MapTracker tracker(s.map, params());
  FixHypotheses h(tracker, s.map, kChi2);
  // A second keyframe's view of the same alignments (1 m and 0.5 deg apart: within the capture range).
  std::vector<ContestedPlace> places = contested();
  places.push_back({1, {{0.9, 0.3, 0.008}, {13.0, -0.3, 0.0}}});
  h.seed(scanAt(s, 0), places);
  EXPECT_EQ(h.registrations(), 4u);
  EXPECT_GE(h.size(), 2u);
  h.seed(scanAt(s, 0), {});
  EXPECT_EQ(h.registrations(), 0u);
  EXPECT_TRUE(h.empty()) << "a seed replaces the hypotheses";
}

TEST(FixHypotheses, TheGateRulesPlacesOut) {
  const Street s = street(std::nullopt);
  MapTracker tracker(s.map, params());
  FixHypotheses h(tracker, s.map, kChi2);
  // A prior near x = -12: only that period survives.
  h.seed(scanAt(s, 0), contested(), [](const TrackResult& r) { return std::abs(r.icp.pose.x + 12) < 3; });
  ASSERT_EQ(h.size(), 1u);
  EXPECT_NEAR(h.hypotheses().front().last.icp.pose.x, -12, 0.5);
}

}  // namespace
}  // namespace radarslam
