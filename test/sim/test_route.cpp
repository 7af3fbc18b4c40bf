// World and route: determinism, the demo route's properties, loops, the second traversal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "radarslam/sim/route.h"
#include "radarslam/sim/world.h"
#include "sim_test_util.h"

using namespace radarslam;
using namespace radarslam::sim;

using simtest::sampleTrajectory;

TEST(SimWorld, SameSeedSameWorldOtherSeedOtherWorld) {
  const World a = generateWorld({}, 7, 1), b = generateWorld({}, 7, 1), c = generateWorld({}, 8, 1);
  ASSERT_EQ(a.segments.size(), b.segments.size());
  ASSERT_EQ(a.circles.size(), b.circles.size());
  for (std::size_t k = 0; k < a.segments.size(); ++k) {
    ASSERT_EQ(a.segments[k].a.x, b.segments[k].a.x);
    ASSERT_EQ(a.segments[k].b.y, b.segments[k].b.y);
  }
  EXPECT_NE(a.street_x, c.street_x);
  EXPECT_GT(a.segments.size(), 500u);  // a city, not a toy
  EXPECT_GT(a.circles.size(), 500u);
}

TEST(SimWorld, SecondTraversalKeepsStaticWorldButChangesCarsAndTraffic) {
  const World t1 = generateWorld({}, 3, 1), t2 = generateWorld({}, 3, 2);
  EXPECT_EQ(t1.street_x, t2.street_x);
  EXPECT_EQ(t1.street_y, t2.street_y);
  auto count = [](const World& w, Material m) {
    return std::count_if(w.segments.begin(), w.segments.end(),
                         [m](const Segment& s) { return s.surface.material == m; });
  };
  const auto facades1 = count(t1, Material::Facade), facades2 = count(t2, Material::Facade);
  const auto cars1 = count(t1, Material::Car), cars2 = count(t2, Material::Car);
  EXPECT_EQ(facades1, facades2);
  EXPECT_NE(cars1, cars2);  // parked cars redrawn
  ASSERT_FALSE(t1.movers.empty());
  EXPECT_NE(t1.movers.front().phase_m, t2.movers.front().phase_m);
}

TEST(SimWorld, RayStopsAtFirstOpaqueWallAndSeesThroughFoliage) {
  World w;
  Surface wall;
  wall.transmission = 0;
  Surface hedge;
  hedge.transmission = 0.5f;
  hedge.material = Material::Hedge;
  w.segments.push_back({{10, -5}, {10, 5}, hedge});
  w.segments.push_back({{20, -5}, {20, 5}, wall});
  w.segments.push_back({{30, -5}, {30, 5}, wall});
  w.street_x = {0}, w.street_y = {0};
  w.buildIndex();
  RayCaster caster(w);
  std::vector<RayHit> hits;
  caster.cast({0, 0}, {1, 0}, 100, {}, hits);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_NEAR(hits[0].range, 10, 1e-9);
  EXPECT_NEAR(hits[1].range, 20, 1e-9);
  EXPECT_NEAR(hits[1].cos_incidence, 1.0, 1e-6);
  caster.cast({0, 0}, {0, 1}, 100, {}, hits);
  EXPECT_TRUE(hits.empty());
}

TEST(SimRoute, DemoRouteIsLongRealisticAndHasLoopsBothWays) {
  const World w = generateWorld({}, 1, 1);
  const Route r = planRoute(w, {}, 1, 1);
  EXPECT_GE(r.length(), 3000.0);
  double vmax = 0, amax = 0;
  std::size_t stopped = 0;
  for (std::size_t k = 1; k < r.samples.size(); ++k) {
    const auto &a = r.samples[k - 1], &b = r.samples[k];
    vmax = std::max(vmax, b.speed);
    EXPECT_GE(b.speed, 0.0);
    EXPECT_GT(b.t_arrive, a.t_depart - 1e-12);
    const double dt = b.t_arrive - a.t_depart;
    if (dt > 1e-6) amax = std::max(amax, std::abs(b.speed - a.speed) / dt);
    if (b.t_depart > b.t_arrive + 1.0) ++stopped;
  }
  EXPECT_LE(vmax, 15.0 + 1e-9);
  EXPECT_GT(vmax, 12.0);        // it does get going on the open road
  EXPECT_LE(amax, 2.5 + 1e-6);  // smooth acceleration (decel limit)
  EXPECT_GE(stopped, 2u);       // stops at some intersections
  // Poses are continuous: no jumps between 0.1 s samples.
  const Trajectory traj = sampleTrajectory(r, 0.1);
  for (std::size_t k = 1; k < traj.size(); ++k)
    ASSERT_LT(std::hypot(traj[k].pose.x - traj[k - 1].pose.x, traj[k].pose.y - traj[k - 1].pose.y), 1.6);
  const auto loops = findLoops(sampleTrajectory(r, 0.25));
  const auto opposite =
      std::count_if(loops.begin(), loops.end(), [](const LoopEvent& e) { return e.opposite_direction; });
  EXPECT_GE(loops.size(), 4u);
  EXPECT_GE(opposite, 2);
  EXPECT_GE(static_cast<long>(loops.size()) - opposite, 1);  // same-direction revisits too
}

TEST(SimRoute, LengthOptionTruncatesAndExtendsWithLaps) {
  const World w = generateWorld({}, 2, 1);
  const Route one = planRoute(w, {}, 2, 1);
  const Route short_route = planRoute(w, {}, 2, 1, 500);
  EXPECT_NEAR(short_route.length(), 500, 2.0);
  EXPECT_EQ(short_route.samples.back().speed, 0.0);  // ends at rest
  const Route two_laps = planRoute(w, {}, 2, 1, one.length() + 200);
  EXPECT_GE(two_laps.length(), one.length() + 198);
}

TEST(SimRoute, SecondTraversalDrivesADifferentLaneLater) {
  const World w = generateWorld({}, 4, 1);
  RouteParams p;
  const Route r1 = planRoute(w, p, 4, 1), r2 = planRoute(w, p, 4, 2);
  EXPECT_GT(r2.start_stamp - r1.start_stamp, 86400LL * kNsPerSec);
  // Lateral distance of traversal 2 from traversal 1 on straight stretches: the lane difference.
  std::vector<double> d;
  for (std::size_t k = 0; k < r2.samples.size(); k += 40) {
    const auto& q = r2.samples[k];
    double best = 1e9;
    for (const auto& s : r1.samples) best = std::min(best, std::hypot(s.x - q.x, s.y - q.y));
    d.push_back(best);
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  EXPECT_NEAR(d[d.size() / 2], std::abs(p.lane_offset_m - p.lane_offset_traversal2_m), 0.15);
}
