// Worlds generated around a route: determinism, nothing on the road, the same objects from both
// directions, the featureless wall, the street network's shape.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "radarslam/sim/route_world.h"
#include "radarslam/sim/street_network.h"
#include "sim_test_util.h"

using namespace radarslam;
using namespace radarslam::sim;

namespace {

const Scene kAllScenes[] = {Scene::Mixed,   Scene::Urban,  Scene::Suburban, Scene::Country,
                            Scene::Carpark, Scene::Avenue, Scene::Wall};

World networkWorld(std::uint64_t seed, Scene scene, int traversal = 1) {
  const StreetNetwork net = generateStreetNetwork(seed, {});
  return generateRouteWorld(roadCentreline(net.lap, {}), {}, {}, scene,
                            scene == Scene::Mixed ? net.zones : std::vector<SceneZone>{}, seed, traversal);
}

/// A street with a curve: 200 m straight, a 90-degree bend of radius 60 m, 150 m straight.
std::vector<RoadPiece> curvedStreet(double hw = 6) {
  std::vector<Vec2> p;
  for (double u = 0; u < 200; u += 4) p.push_back({u, 0});
  for (int k = 0; k <= 24; ++k) {
    const double a = M_PI / 2 * k / 24;
    p.push_back({200 + 60 * std::sin(a), 60 - 60 * std::cos(a)});
  }
  for (double u = 4; u <= 150; u += 4) p.push_back({260, 60 + u});
  std::vector<RoadPiece> r;
  for (std::size_t k = 1; k < p.size(); ++k) r.push_back({p[k - 1], p[k], hw});
  return r;
}

std::vector<RoadPiece> reversed(const std::vector<RoadPiece>& r) {
  std::vector<RoadPiece> out;
  for (std::size_t k = r.size(); k-- > 0;) out.push_back({r[k].b, r[k].a, r[k].half_width});
  return out;
}

using Key = std::tuple<double, double, double, double, int>;
/// Static objects as a sorted list (segment end points in a canonical order), for set equality.
std::vector<Key> objectSet(const World& w) {
  std::vector<Key> v;
  for (const auto& s : w.segments) {
    const bool swap = std::tie(s.b.x, s.b.y) < std::tie(s.a.x, s.a.y);
    const Vec2 a = swap ? s.b : s.a, b = swap ? s.a : s.b;
    v.emplace_back(a.x, a.y, b.x, b.y, static_cast<int>(s.surface.material));
  }
  for (const auto& c : w.circles) v.emplace_back(c.centre.x, c.centre.y, c.radius, -1, 100);
  std::sort(v.begin(), v.end());
  return v;
}

double segmentDistance(Vec2 p, Vec2 q, Vec2 a, Vec2 b) {
  const Vec2 r = q - p, s = b - a;
  const double den = r.cross(s);
  if (std::abs(den) > 1e-12) {
    const double t = (a - p).cross(s) / den, u = (a - p).cross(r) / den;
    if (t >= 0 && t <= 1 && u >= 0 && u <= 1) return 0;
  }
  return std::min({distanceToSegment(p, a, b), distanceToSegment(q, a, b), distanceToSegment(a, p, q),
                   distanceToSegment(b, p, q)});
}

/// Smallest (distance - half-width) of any static object to any road piece, by brute force
/// (a bounding-box test first: only pieces within 2 m of an object's box can be worse than 2 m).
double worstClearance(const World& w, const std::vector<RoadPiece>& roads) {
  double worst = 2.0;
  auto near = [](const RoadPiece& r, double x0, double y0, double x1, double y1) {
    const double g = r.half_width + 2.0;
    return std::min(r.a.x, r.b.x) - g <= x1 && std::max(r.a.x, r.b.x) + g >= x0 &&
           std::min(r.a.y, r.b.y) - g <= y1 && std::max(r.a.y, r.b.y) + g >= y0;
  };
  for (const auto& r : roads) {
    for (const auto& s : w.segments)
      if (near(r, std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y), std::max(s.a.x, s.b.x),
               std::max(s.a.y, s.b.y)))
        worst = std::min(worst, segmentDistance(s.a, s.b, r.a, r.b) - r.half_width);
    for (const auto& c : w.circles)
      if (near(r, c.centre.x - c.radius, c.centre.y - c.radius, c.centre.x + c.radius, c.centre.y + c.radius))
        worst = std::min(worst, distanceToSegment(c.centre, r.a, r.b) - c.radius - r.half_width);
  }
  return worst;
}

}  // namespace

TEST(SimRouteWorld, SameSeedSameWorldOtherSeedOtherWorld) {
  const World a = networkWorld(5, Scene::Mixed), b = networkWorld(5, Scene::Mixed),
              c = networkWorld(6, Scene::Mixed);
  EXPECT_EQ(objectSet(a), objectSet(b));
  ASSERT_EQ(a.movers.size(), b.movers.size());
  for (std::size_t k = 0; k < a.movers.size(); ++k) EXPECT_EQ(a.movers[k].phase_m, b.movers[k].phase_m);
  EXPECT_NE(objectSet(a), objectSet(c));
  EXPECT_GT(a.segments.size(), 500u);
  EXPECT_GT(a.circles.size(), 300u);
}

TEST(SimRouteWorld, SameSeedSameScanBytes) {
  for (const char* world : {"network"}) {
    SimulationConfig cfg = simtest::smallConfig(3, 3);
    cfg.world_type = world;
    Simulation s1(cfg), s2(cfg);
    CObservationRadarScan a, b;
    for (std::size_t i = 0; i < 3; ++i) {
      s1.render(i, a);
      s2.render(i, b);
      EXPECT_EQ(a.power, b.power) << world << " scan " << i;
      EXPECT_EQ(a.azimuth_stamps_ns, b.azimuth_stamps_ns);
    }
    std::size_t lit = std::count_if(a.power.begin(), a.power.end(), [](std::uint8_t v) { return v > 60; });
    EXPECT_GT(lit, 100u) << "the world is visible";
  }
}

TEST(SimRouteWorld, NoObjectOnTheRoadInAnyScene) {
  const StreetNetwork net = generateStreetNetwork(2, {});
  const auto roads = roadCentreline(net.lap, {});
  const RouteWorldParams params;
  for (Scene scene : kAllScenes) {
    const World w = generateRouteWorld(roads, params, {}, scene,
                                       scene == Scene::Mixed ? net.zones : std::vector<SceneZone>{}, 2, 1);
    EXPECT_GT(w.segments.size() + w.circles.size(), 50u) << sceneName(scene);
    EXPECT_GT(worstClearance(w, roads), params.margin_m) << sceneName(scene);
  }
  // A route that crosses itself and revisits a street at an offset (as a drifting real drive).
  auto street = curvedStreet();
  auto back = reversed(curvedStreet());
  for (auto& r : back) r.a.y += 3.0, r.b.y += 3.0;
  street.insert(street.end(), back.begin(), back.end());
  street.push_back({{100, -80}, {100, 140}, 5});
  const World w = generateRouteWorld(street, params, {}, Scene::Urban, {}, 4, 1);
  EXPECT_GT(worstClearance(w, street), params.margin_m);
}

TEST(SimRouteWorld, RevisitedStreetHasTheSameObjectsFromBothDirections) {
  const auto street = curvedStreet();
  auto twice = street;
  const auto back = reversed(street);
  twice.insert(twice.end(), back.begin(), back.end());
  for (Scene scene : kAllScenes) {
    const auto forward = objectSet(generateRouteWorld(street, {}, {}, scene, {}, 9, 1));
    EXPECT_GT(forward.size(), 10u) << sceneName(scene);
    EXPECT_EQ(forward, objectSet(generateRouteWorld(back, {}, {}, scene, {}, 9, 1))) << sceneName(scene);
    EXPECT_EQ(forward, objectSet(generateRouteWorld(twice, {}, {}, scene, {}, 9, 1))) << sceneName(scene);
  }
}

TEST(SimRouteWorld, NetworkLoopDrivenBothWaysHasNoDuplicatedObjects) {
  const World w = networkWorld(3, Scene::Urban);
  std::size_t duplicates = 0;
  for (std::size_t i = 0; i < w.segments.size(); ++i)
    for (std::size_t j = i + 1; j < w.segments.size(); ++j) {
      const auto &s = w.segments[i], &t = w.segments[j];
      const bool same = ((s.a - t.a).norm() < 0.3 && (s.b - t.b).norm() < 0.3) ||
                        ((s.a - t.b).norm() < 0.3 && (s.b - t.a).norm() < 0.3);
      duplicates += same;
    }
  EXPECT_EQ(duplicates, 0u);
}

TEST(SimRouteWorld, ParkedCarsChangePerTraversalTheRestDoesNot) {
  const World t1 = networkWorld(4, Scene::Urban, 1), t2 = networkWorld(4, Scene::Urban, 2);
  auto without = [](const World& w, bool cars) {
    World c = w;
    c.segments.erase(
        std::remove_if(c.segments.begin(), c.segments.end(),
                       [&](const Segment& s) { return (s.surface.material == Material::Car) != cars; }),
        c.segments.end());
    c.circles.clear();
    return objectSet(c);
  };
  EXPECT_EQ(without(t1, false), without(t2, false));  // facades etc.
  EXPECT_NE(without(t1, true), without(t2, true));    // parked cars
  ASSERT_FALSE(t1.movers.empty());
  EXPECT_NE(t1.movers.front().phase_m, t2.movers.front().phase_m);
}

TEST(SimRouteWorld, WallSceneIsOneSmoothFacadeOnOneSideAndNothingOnTheOther) {
  std::vector<RoadPiece> road;  // 340 m: inside one 350 m wall cell, so one side throughout
  for (double u = 0; u < 340; u += 4) road.push_back({{u, 0}, {u + 4, 0}, 6});
  const World w = generateRouteWorld(road, {}, {}, Scene::Wall, {}, 1, 1);
  EXPECT_TRUE(w.circles.empty());
  ASSERT_FALSE(w.segments.empty());
  const bool left = w.segments.front().a.y > 0;
  double length = 0;
  for (const auto& s : w.segments) {
    EXPECT_EQ(s.a.y > 0, left) << "an object on the empty side";
    EXPECT_NEAR(s.a.y, s.b.y, 1e-9);  // parallel to the road: no corners, no setbacks
    EXPECT_NEAR(std::abs(s.a.y), std::abs(w.segments.front().a.y), 1e-9);
    EXPECT_EQ(s.surface.texture_seed, w.segments.front().surface.texture_seed);
    EXPECT_GE(s.surface.texture_period_m, 1000.0f);  // no texture along it
    EXPECT_LT(s.surface.roughness, 0.1f);
    length += (s.b - s.a).norm();
  }
  EXPECT_GT(length, 300.0);
  // In the mixed network, the wall zone lines one side of the long straight only.
  const StreetNetwork net = generateStreetNetwork(1, {});
  ASSERT_EQ(net.zones.size(), 1u);
  EXPECT_GE(net.wall_length_m, 300.0);
  EXPECT_LE(net.wall_length_m, 400.0);
  const World mixed = networkWorld(1, Scene::Mixed);
  const SceneZone& z = net.zones.front();
  const Vec2 axis = (z.b - z.a) * (1.0 / (z.b - z.a).norm());
  int sides[2] = {0, 0};
  for (const auto& seg : mixed.segments)
    for (const Vec2 q : {seg.a, seg.b}) {
      const double along = (q - z.a).dot(axis), across = axis.cross(q - z.a);
      if (along > 0 && along < (z.b - z.a).norm() && std::abs(across) < 60) ++sides[across > 0];
    }
  for (const auto& c : mixed.circles) {
    const double along = (c.centre - z.a).dot(axis), across = axis.cross(c.centre - z.a);
    if (along > 0 && along < (z.b - z.a).norm() && std::abs(across) < 60) ++sides[across > 0];
  }
  EXPECT_GT(sides[0] + sides[1], 0);
  EXPECT_EQ(std::min(sides[0], sides[1]), 0) << sides[0] << " / " << sides[1];
}

TEST(SimStreetNetwork, HasCurvesSkewJunctionsARoundaboutAndRevisitsBothWays) {
  const StreetNetwork net = generateStreetNetwork(1, {});
  ASSERT_GT(net.lap.size(), 20u);
  EXPECT_LT((net.lap.front().p - net.lap.back().p).norm(), 1e-9) << "laps chain";
  int skew = 0;
  double min_hw = 1e9, max_hw = 0;
  for (std::size_t k = 1; k + 1 < net.lap.size(); ++k) {
    const Vec2 d1 = net.lap[k].p - net.lap[k - 1].p, d2 = net.lap[k + 1].p - net.lap[k].p;
    if (d1.norm() < 1 || d2.norm() < 1) continue;
    const double turn = std::acos(std::clamp(d1.dot(d2) / d1.norm() / d2.norm(), -1.0, 1.0)) * 180 / M_PI;
    skew += turn > 20 && std::abs(turn - 90) > 10;
    min_hw = std::min(min_hw, net.lap[k].half_width), max_hw = std::max(max_hw, net.lap[k].half_width);
  }
  EXPECT_GE(skew, 4);
  EXPECT_GE(max_hw - min_hw, 1.5);
  const Route route = planRouteThrough(net.lap, {}, 1, 1);
  Trajectory t;
  for (double s = 0; s < route.duration(); s += 1.0) {
    const StampNs stamp = route.start_stamp + static_cast<StampNs>(s * 1e9);
    t.push_back({stamp, route.poseAt(stamp)});
  }
  const auto loops = findLoops(t);
  EXPECT_TRUE(
      std::any_of(loops.begin(), loops.end(), [](const LoopEvent& e) { return e.opposite_direction; }));
  EXPECT_GT(route.length(), 2500.0);
  double max_speed = 0;
  for (const auto& s : route.samples) max_speed = std::max(max_speed, s.speed);
  EXPECT_LE(max_speed, 15.0 + 1e-9);
}
