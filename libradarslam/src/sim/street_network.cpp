#include "radarslam/sim/street_network.h"

#include <algorithm>
#include <cmath>

#include "radarslam/sim/rng.h"

namespace radarslam::sim {

namespace {

Vec2 dir(double angle) { return {std::cos(angle), std::sin(angle)}; }

class LapBuilder {
 public:
  std::vector<RouteWaypoint> lap;

  void add(Vec2 p, double radius, double speed, double half_width, bool intersection = false) {
    lap.push_back({p, radius, speed, intersection, half_width});
  }

  /// Round a circle (centre c, radius r) from angle a0 through `sweep` (> 0, increasing angle),
  /// the entry vertex already added; ends with the exit vertex.
  void circulate(Vec2 c, double r, double a0, double sweep, double speed, double half_width) {
    const int m = std::max(2, static_cast<int>(std::ceil(sweep / (M_PI / 6))));
    for (int k = 1; k <= m; ++k) add(c + dir(a0 + sweep * k / m) * r, 0.9 * r, speed, half_width, k == m);
  }
};

}  // namespace

StreetNetwork generateStreetNetwork(std::uint64_t seed, const RouteParams& params) {
  Rng rng(hashCombine(seed, 0x57EE7));
  const double fast = params.country_speed_mps, town = params.city_speed_mps;
  const double slow = std::min(town, 8.0), crawl = std::min(town, 6.0);
  StreetNetwork net;
  LapBuilder b;

  // The long straight from the cul-de-sac S, then a wide curve to the roundabout.
  const double theta0 = rng.uniform(0, 2 * M_PI);
  const Vec2 S{0, 0};
  const double straight = rng.uniform(430, 470);
  b.add(S, 9, fast, 7);
  const Vec2 A = S + dir(theta0) * straight;
  b.add(A, 80, fast, 7);
  const double turn = (rng.chance(0.5) ? 1 : -1) * rng.uniform(50, 75) * M_PI / 180;
  const double curve_radius = rng.uniform(220, 320);
  const int curve_steps = 6;
  std::vector<Vec2> curve{A};
  for (int k = 1; k <= curve_steps; ++k) {
    curve.push_back(curve.back() + dir(theta0 + turn * (k - 0.5) / curve_steps) *
                                       (curve_radius * std::abs(turn) / curve_steps));
    b.add(curve.back(), curve_radius, fast, 6.5);
  }
  const double theta1 = theta0 + turn;
  const Vec2 B = curve.back() + dir(theta1) * rng.uniform(150, 220);
  b.add(B, 8, town, 6, true);
  const double rr = rng.uniform(13, 17);  // the roundabout's centreline radius
  const Vec2 C = B + dir(theta1) * rr;
  const double phi_b = theta1 + M_PI;  // arm to B, seen from the centre
  const double sweep = rng.uniform(200, 240) * M_PI / 180;
  const double phi_x = phi_b + sweep;  // arm to the junction
  b.circulate(C, rr, phi_b, sweep, slow, 5.5);
  const Vec2 X = C + dir(phi_x) * rr;
  const Vec2 J = X + dir(phi_x) * rng.uniform(180, 240);
  b.add(J, 12, town, 6, true);

  // The loop: a star-shaped heptagon round a centre beyond J (so its corners are 35-65 degrees,
  // never square), with varying widths and corner radii (curved streets).
  const double loop_radius = rng.uniform(120, 150);
  const Vec2 L = J + dir(phi_x) * loop_radius;
  const double psi_j = phi_x + M_PI;
  std::vector<Vec2> ring;
  std::vector<double> ring_hw, ring_radius;
  for (int k = 1; k <= 6; ++k) {
    const double psi = psi_j + k * 2 * M_PI / 7 + rng.uniform(-0.15, 0.15);
    ring.push_back(L + dir(psi) * (loop_radius * rng.uniform(0.8, 1.2)));
    ring_hw.push_back(rng.uniform(4.5, 5.5));
    ring_radius.push_back(rng.uniform(15, 45));
  }
  const double hw_j = rng.uniform(4.5, 5.5);
  for (std::size_t k = 0; k < ring.size(); ++k) b.add(ring[k], ring_radius[k], town, ring_hw[k]);
  b.add(J, 12, town, hw_j, true);
  // A U-turn round the roundabout, then the loop the other way.
  b.add(X, 8, town, 6, true);
  b.circulate(C, rr, phi_x, 2 * M_PI, slow, 5.5);
  b.add(J, 12, town, 6, true);
  for (std::size_t k = ring.size(); k-- > 0;)
    b.add(ring[k], ring_radius[k], town, k + 1 < ring.size() ? ring_hw[k + 1] : hw_j);
  b.add(J, 12, town, ring_hw[0], true);
  // Back: round the roundabout to the B arm, the curve and the straight in reverse.
  b.add(X, 8, town, 6, true);
  b.circulate(C, rr, phi_x, 2 * M_PI - sweep, slow, 5.5);
  for (std::size_t k = curve.size(); k-- > 0;) {  // the curve's vertices back to A
    const bool first = k + 1 == curve.size();
    b.add(curve[k], k == 0 ? 80 : curve_radius, first ? town : fast, first ? 6 : 6.5);
  }
  // The cul-de-sac behind S: round its turning circle and end at S heading out again.
  b.add(S, 6, fast, 7);
  const double rb = 9;
  const Vec2 Q = S - dir(theta0) * (rb + 6);
  const Vec2 neck = S - dir(theta0) * 6;
  b.add(neck, 6, crawl, 5);
  b.circulate(Q, rb, theta0 + M_PI / 6, 2 * M_PI - M_PI / 3, crawl, 5);
  b.add(neck, 6, crawl, 5);
  b.add(S, 9, town, 5);
  net.lap = std::move(b.lap);

  // The degenerate stretch: a smooth wall along most of the straight, on one side only.
  const double w0 = 60, w1 = std::min(straight - 40, 360.0);
  net.zones.push_back({S + dir(theta0) * w0, S + dir(theta0) * w1, 30, Scene::Wall});
  net.wall_length_m = w1 - w0 + 60;
  return net;
}

}  // namespace radarslam::sim
