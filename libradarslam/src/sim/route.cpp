#include "radarslam/sim/route.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "radarslam/sim/rng.h"
#include "world_builder.h"

namespace radarslam::sim {

namespace {

using Waypoint = RouteWaypoint;

struct RawPoint {
  Vec2 p;
  double speed_limit;
  double dwell_s = 0;
  double half_width = 6;
};

double wrapAngle(double a) { return std::remainder(a, 2 * M_PI); }

/// The tour in grid-node indices; it starts and ends at node (0,0) so that laps chain.
std::vector<Waypoint> tourWaypoints(const World& w, const RouteParams& p) {
  const int nx = w.streetsX(), ny = w.streetsY();
  const int a = std::min(2, nx - 1), b = std::min(2, ny - 1);
  std::vector<Waypoint> wps;
  auto go = [&](int i, int j, double speed) {  // straight leg to node (i,j), one grid step at a time
    if (wps.empty()) {
      wps.push_back({w.node(i, j), p.corner_radius_m, speed, true});
      return;
    }
    int ci = 0, cj = 0;
    for (int qi = 0; qi < nx; ++qi)
      for (int qj = 0; qj < ny; ++qj)
        if (std::abs(w.street_x[qi] - wps.back().p.x) < 1e-6 &&
            std::abs(w.street_y[qj] - wps.back().p.y) < 1e-6)
          ci = qi, cj = qj;
    while (ci != i || cj != j) {
      ci += (i > ci) - (i < ci);
      cj += (j > cj) - (j < cj);
      wps.push_back({w.node(ci, cj), p.corner_radius_m, speed, true});
    }
  };
  const double city = p.city_speed_mps;
  go(0, 0, city);
  go(a, 0, city), go(a, b, city), go(0, b, city), go(0, 0, city);  // A: a loop round four blocks
  go(nx - 1, 0, city);                                             // B: revisit, same direction
  go(nx - 1, 1, city);                                             // C: out to the countryside
  for (std::size_t k = 1; k < w.country_road.size(); ++k)
    wps.push_back({w.country_road[k], p.country_corner_radius_m, p.country_speed_mps, false});
  wps.back().radius = p.corner_radius_m;
  wps.back().intersection = true;
  for (int i = nx - 2; i >= 0; --i) go(i, ny - 1, p.corridor_speed_mps);  // D: the corridor
  go(0, b, city), go(a, b, city), go(a, 0, city);  // E: revisits in the opposite direction
  go(0, 0, city);                                  // F: back to the start, opposite again
  const int c = std::min(1, nx - 1), d = std::min(1, ny - 1);
  go(0, d, city), go(c, d, city), go(c, 0, city), go(0, 0, city);  // G: opposite, then same again
  return wps;
}

/// Centreline through the waypoints with circular fillets at the corners; marks stops.
std::vector<RawPoint> filletedPath(const std::vector<Waypoint>& wps, const RouteParams& p, Rng& rng) {
  std::vector<RawPoint> out;
  out.push_back(
      {wps[0].p, wps.size() > 1 ? wps[1].speed_in : 0.0, 0.0, wps.size() > 1 ? wps[1].half_width : 6.0});
  for (std::size_t k = 1; k < wps.size(); ++k) {
    const Waypoint& w = wps[k];
    const double speed = w.speed_in;
    if (k + 1 == wps.size()) {
      out.push_back({w.p, speed, 0.0, w.half_width});
      break;
    }
    const Vec2 d1 = detail::unit(w.p - wps[k - 1].p), d2 = detail::unit(wps[k + 1].p - w.p);
    const double phi = std::acos(std::clamp(d1.dot(d2), -1.0, 1.0));
    if (phi < 0.05) {  // straight through: maybe a stop line before the intersection
      if (w.intersection && rng.chance(p.stop_probability)) {
        const double before = std::min(12.0, 0.4 * (w.p - wps[k - 1].p).norm());
        out.push_back({w.p - d1 * before, speed, rng.uniform(p.stop_min_s, p.stop_max_s), w.half_width});
      }
      out.push_back({w.p, speed, 0.0, w.half_width});
      continue;
    }
    const double len_in = (w.p - wps[k - 1].p).norm(), len_out = (wps[k + 1].p - w.p).norm();
    double tangent = w.radius * std::tan(phi / 2);
    tangent = std::min(tangent, 0.45 * std::min(len_in, len_out));
    const double radius = tangent / std::tan(phi / 2);
    const Vec2 start = w.p - d1 * tangent;
    const double sign = d1.cross(d2) > 0 ? 1.0 : -1.0;
    const Vec2 n1{-d1.y * sign, d1.x * sign};
    const Vec2 centre = start + n1 * radius;
    const Vec2 r0 = start - centre;
    const int steps = std::max(2, static_cast<int>(phi * radius / 0.5));
    for (int q = 0; q <= steps; ++q) {
      const double a = sign * phi * q / steps;
      const Vec2 r{r0.x * std::cos(a) - r0.y * std::sin(a), r0.x * std::sin(a) + r0.y * std::cos(a)};
      out.push_back({centre + r, q == 0 ? speed : wps[k + 1].speed_in, 0.0,
                     q == 0 ? w.half_width : wps[k + 1].half_width});
    }
  }
  return out;
}

Route buildRoute(const std::vector<RawPoint>& raw, const RouteParams& p, double lane_offset,
                 double max_length) {
  constexpr double ds = 0.25;
  Route route;
  // Resample the centreline at ds, carrying speed limits and stops.
  struct Dense {
    Vec2 p;
    double yaw, limit, dwell;
  };
  std::vector<Dense> dense;
  double carry = 0;  // arc length already covered into the current raw segment
  for (std::size_t k = 1; k < raw.size(); ++k) {
    const Vec2 e = raw[k].p - raw[k - 1].p;
    const double len = e.norm();
    if (len < 1e-9) {
      if (!dense.empty()) dense.back().dwell += raw[k].dwell_s;
      continue;
    }
    const Vec2 d = e * (1.0 / len);
    const double yaw = std::atan2(d.y, d.x);
    double u = carry;
    for (; u < len; u += ds) dense.push_back({raw[k - 1].p + d * u, yaw, raw[k].speed_limit, 0.0});
    carry = u - len;
    if (raw[k].dwell_s > 0) dense.push_back({raw[k].p, yaw, raw[k].speed_limit, raw[k].dwell_s});
  }
  const std::size_t n = dense.size();
  // Curvature ramps: the centreline averaged over curvature_transition_m. A moving average turns
  // each fillet's curvature step into a linear ramp of that length (a clothoid-like transition),
  // so the yaw rate changes smoothly as a real car's does; yaw from the smoothed points.
  const auto half = static_cast<std::size_t>(std::lround(p.curvature_transition_m / 2 / ds));
  if (half > 0 && n > 2) {
    // The path continued straight beyond both ends (along the first and last yaw), so the ends
    // are averaged like any other point instead of keeping a corner.
    std::vector<Vec2> padded;
    const Vec2 d0{std::cos(dense.front().yaw), std::sin(dense.front().yaw)};
    const Vec2 d1{std::cos(dense.back().yaw), std::sin(dense.back().yaw)};
    for (std::size_t k = half; k > 0; --k)
      padded.push_back(dense.front().p - d0 * (ds * static_cast<double>(k)));
    for (const Dense& q : dense) padded.push_back(q.p);
    for (std::size_t k = 1; k <= half; ++k)
      padded.push_back(dense.back().p + d1 * (ds * static_cast<double>(k)));
    std::vector<Vec2> sum(padded.size() + 1, Vec2{0, 0});
    for (std::size_t k = 0; k < padded.size(); ++k) sum[k + 1] = sum[k] + padded[k];
    std::vector<Vec2> smooth(n);
    for (std::size_t k = 0; k < n; ++k)  // padded index of dense[k] is k + half
      smooth[k] = (sum[k + 2 * half + 1] - sum[k]) * (1.0 / static_cast<double>(2 * half + 1));
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t lo = k >= 2 ? k - 2 : 0, hi = std::min(n - 1, k + 2);
      const Vec2 d = smooth[hi] - smooth[lo];
      if (d.norm() > 1e-3) dense[k].yaw = std::atan2(d.y, d.x);
      dense[k].p = smooth[k];
    }
  }
  // Lane offset (left of travel direction = (d.y, -d.x), see world.cpp), then arc length.
  std::vector<double> s(n, 0.0), kappa(n, 0.0), dkappa(n, 0.0);
  for (auto& q : dense) q.p = q.p + Vec2{std::sin(q.yaw), -std::cos(q.yaw)} * lane_offset;
  for (std::size_t k = 1; k < n; ++k) s[k] = s[k - 1] + (dense[k].p - dense[k - 1].p).norm();
  constexpr std::size_t kWindow = 8;     // +-2 m
  for (std::size_t k = 0; k < n; ++k) {  // signed curvature
    const std::size_t lo = k >= kWindow ? k - kWindow : 0, hi = std::min(n - 1, k + kWindow);
    if (s[hi] - s[lo] > 0.1) kappa[k] = wrapAngle(dense[hi].yaw - dense[lo].yaw) / (s[hi] - s[lo]);
  }
  for (std::size_t k = 0; k < n; ++k) {  // its rate of change along the path
    const std::size_t lo = k >= kWindow ? k - kWindow : 0, hi = std::min(n - 1, k + kWindow);
    if (s[hi] - s[lo] > 0.1) dkappa[k] = std::abs(kappa[hi] - kappa[lo]) / (s[hi] - s[lo]);
  }
  std::size_t end = n;
  if (max_length > 0)
    while (end > 2 && s[end - 1] > max_length) --end;
  // Speed profile: limits; in turns lateral acceleration v^2 k, yaw rate v k and the yaw
  // acceleration d(v k)/dt = v^2 dk/ds + k dv/dt, each term held to half the limit; stops; then
  // acceleration limits both ways (gentler in a turn: the k dv/dt term).
  const double max_yaw_rate = p.max_yaw_rate_dps * M_PI / 180,
               max_yaw_accel = p.max_yaw_accel_dps2 * M_PI / 180;
  auto accel = [&](std::size_t k, double limit) {
    return std::abs(kappa[k]) > 1e-6 ? std::min(limit, 0.5 * max_yaw_accel / std::abs(kappa[k])) : limit;
  };
  std::vector<double> v(end);
  for (std::size_t k = 0; k < end; ++k) {
    const double curvature = std::abs(kappa[k]);
    v[k] = dense[k].limit;
    if (curvature > 1e-6)
      v[k] = std::min({v[k], std::sqrt(p.lateral_accel_mps2 / curvature), max_yaw_rate / curvature});
    if (dkappa[k] > 1e-9) v[k] = std::min(v[k], std::sqrt(0.5 * max_yaw_accel / dkappa[k]));
    if (dense[k].dwell > 0) v[k] = 0;
  }
  v[0] = 0, v[end - 1] = 0;
  for (std::size_t k = 1; k < end; ++k)
    v[k] = std::min(v[k], std::sqrt(v[k - 1] * v[k - 1] + 2 * accel(k, p.accel_mps2) * (s[k] - s[k - 1])));
  for (std::size_t k = end - 1; k-- > 0;)
    v[k] = std::min(v[k], std::sqrt(v[k + 1] * v[k + 1] + 2 * accel(k, p.decel_mps2) * (s[k + 1] - s[k])));
  double t = 0;
  for (std::size_t k = 0; k < end; ++k) {
    if (k > 0) {
      const double step = s[k] - s[k - 1];
      if (step > 1e-9) t += 2 * step / std::max(v[k] + v[k - 1], 1e-3);
    }
    RouteSample r;
    r.s = s[k];
    r.t_arrive = t;
    t += dense[k].dwell;
    r.t_depart = t;
    r.x = dense[k].p.x, r.y = dense[k].p.y, r.yaw = dense[k].yaw, r.speed = v[k];
    if (!route.samples.empty() && r.s <= route.samples.back().s + 1e-9) {  // duplicate point (a stop)
      route.samples.back().t_depart = r.t_depart;
      continue;
    }
    route.samples.push_back(r);
  }
  return route;
}

}  // namespace

Route planRouteThrough(const std::vector<RouteWaypoint>& lap, const RouteParams& params, std::uint64_t seed,
                       int traversal, double min_length_m, double min_duration_s) {
  if (traversal < 1) throw std::invalid_argument("traversal must be >= 1");
  if (lap.size() < 2) throw std::invalid_argument("a route needs at least two waypoints");
  const double lane = traversal == 1 ? params.lane_offset_m : params.lane_offset_traversal2_m;
  Route route;
  for (int laps = 1; laps <= 50; ++laps) {
    std::vector<Waypoint> wps;
    for (int k = 0; k < laps; ++k) wps.insert(wps.end(), k == 0 ? lap.begin() : lap.begin() + 1, lap.end());
    Rng rng(hashCombine(hashCombine(seed, 3), traversal));
    const std::vector<RawPoint> raw = filletedPath(wps, params, rng);
    route = buildRoute(raw, params, lane, min_length_m);
    const bool long_enough = min_length_m <= 0 || route.length() >= min_length_m - 1.0;
    if (long_enough && route.duration() >= min_duration_s) break;
  }
  route.traversal = traversal;
  const double start = params.start_time_s + (traversal - 1) * params.traversal2_delay_s;
  route.start_stamp = static_cast<StampNs>(std::llround(start * 1e6)) * kNsPerUs;
  return route;
}

Route planRoute(const World& world, const RouteParams& params, std::uint64_t seed, int traversal,
                double min_length_m, double min_duration_s) {
  if (traversal < 1) throw std::invalid_argument("traversal must be >= 1");
  return planRouteThrough(tourWaypoints(world, params), params, seed, traversal, min_length_m,
                          min_duration_s);
}

std::vector<RoadPiece> roadCentreline(const std::vector<RouteWaypoint>& lap, const RouteParams& params,
                                      double max_piece_m) {
  Rng rng(0);  // stops only add points on the centreline
  const std::vector<RawPoint> raw = filletedPath(lap, params, rng);
  std::vector<RoadPiece> pieces;
  for (std::size_t k = 1; k < raw.size(); ++k) {
    const Vec2 a = raw[k - 1].p, e = raw[k].p - a;
    const double len = e.norm();
    if (len < 1e-9) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(len / max_piece_m)));
    for (int q = 0; q < n; ++q)
      pieces.push_back({a + e * (static_cast<double>(q) / n), a + e * (static_cast<double>(q + 1) / n),
                        raw[k].half_width});
  }
  return pieces;
}

namespace {
std::size_t sampleIndexAt(const std::vector<RouteSample>& s, double t) {
  const auto it =
      std::upper_bound(s.begin(), s.end(), t, [](double v, const RouteSample& r) { return v < r.t_arrive; });
  return it == s.begin() ? 0 : static_cast<std::size_t>(it - s.begin()) - 1;
}
}  // namespace

mrpt::math::TPose2D Route::poseAt(StampNs stamp) const {
  if (samples.empty()) return {};
  const double t = toSeconds(stamp - start_stamp);
  const std::size_t k = sampleIndexAt(samples, t);
  const RouteSample& a = samples[k];
  if (t <= a.t_depart || k + 1 == samples.size()) return {a.x, a.y, a.yaw};
  const RouteSample& b = samples[k + 1];
  const double f = std::clamp((t - a.t_depart) / std::max(b.t_arrive - a.t_depart, 1e-9), 0.0, 1.0);
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), wrapAngle(a.yaw + f * wrapAngle(b.yaw - a.yaw))};
}

double Route::speedAt(StampNs stamp) const {
  if (samples.empty()) return 0;
  const double t = toSeconds(stamp - start_stamp);
  const std::size_t k = sampleIndexAt(samples, t);
  if (t <= samples[k].t_depart || k + 1 == samples.size())
    return t <= samples[k].t_depart && samples[k].t_depart > samples[k].t_arrive ? 0.0 : samples[k].speed;
  const double f = (t - samples[k].t_depart) / std::max(samples[k + 1].t_arrive - samples[k].t_depart, 1e-9);
  return samples[k].speed + std::clamp(f, 0.0, 1.0) * (samples[k + 1].speed - samples[k].speed);
}

StampNs Route::stampAtDistance(double s) const {
  const auto it = std::lower_bound(samples.begin(), samples.end(), s,
                                   [](const RouteSample& r, double v) { return r.s < v; });
  const RouteSample& r = it == samples.end() ? samples.back() : *it;
  return start_stamp + static_cast<StampNs>(std::llround(r.t_arrive * 1e9));
}

std::vector<LoopEvent> findLoops(const Trajectory& traj, double radius_m, double min_gap_s) {
  // A revisit continues while the matched earlier poses stay contiguous (within 20 s of the
  // previous match) and the direction (same/opposite) does not change; otherwise a new event.
  std::vector<LoopEvent> events;
  bool in_event = false;
  std::size_t prev_j = 0;
  const StampNs gap = static_cast<StampNs>(min_gap_s * 1e9), contiguous = 20 * kNsPerSec;
  for (std::size_t i = 0; i < traj.size(); ++i) {
    double best = radius_m;
    std::size_t best_j = i;
    for (std::size_t j = 0; j < i && traj[i].stamp - traj[j].stamp > gap; ++j) {
      const double d = std::hypot(traj[i].pose.x - traj[j].pose.x, traj[i].pose.y - traj[j].pose.y);
      if (d < best) best = d, best_j = j;
    }
    if (best_j == i) {
      in_event = false;
      continue;
    }
    const bool opposite = std::abs(wrapAngle(traj[i].pose.phi - traj[best_j].pose.phi)) > 2 * M_PI / 3;
    const bool continues = in_event && events.back().opposite_direction == opposite &&
                           std::abs(traj[best_j].stamp - traj[prev_j].stamp) < contiguous;
    if (!continues) events.push_back({i, best_j, best, opposite});
    in_event = true;
    prev_j = best_j;
  }
  return events;
}

}  // namespace radarslam::sim
