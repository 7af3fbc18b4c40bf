#include "radarslam/sim/world.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "radarslam/sim/rng.h"
#include "world_builder.h"

namespace radarslam::sim {

double Vec2::norm() const { return std::hypot(x, y); }

namespace {

using namespace detail;

constexpr std::uint32_t kCircleBit = 0x80000000u;

double polylineLength(const std::vector<Vec2>& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

/// Point and direction at arc length s along a polyline.
void polylineAt(const std::vector<Vec2>& p, double s, Vec2& pos, Vec2& dir) {
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double l = (p[i] - p[i - 1]).norm();
    if (s <= l || i + 1 == p.size()) {
      dir = unit(p[i] - p[i - 1]);
      pos = p[i - 1] + dir * std::min(s, l);
      return;
    }
    s -= l;
  }
  pos = p.back();
  dir = {1, 0};
}

}  // namespace

World generateWorld(const WorldParams& params, std::uint64_t seed, int traversal) {
  World w;
  w.params = params;
  w.seed = seed;
  Rng rng(hashCombine(seed, 1));                           // the static world
  Rng trng(hashCombine(hashCombine(seed, 2), traversal));  // what changes between traversals
  Builder build(w, rng);

  const int nx = params.blocks_x + 1, ny = params.blocks_y + 1;
  w.street_x.assign(nx, 0.0);
  w.street_y.assign(ny, 0.0);
  for (int i = 1; i < nx; ++i)
    w.street_x[i] = w.street_x[i - 1] + rng.uniform(params.block_min_m, params.block_max_m);
  for (int j = 1; j < ny; ++j)
    w.street_y[j] = w.street_y[j - 1] + rng.uniform(params.block_min_m, params.block_max_m);
  for (int i = 0; i < nx; ++i)
    w.half_width_x.push_back(rng.uniform(params.street_half_width_min_m, params.street_half_width_max_m));
  for (int j = 0; j < ny; ++j)
    w.half_width_y.push_back(rng.uniform(params.street_half_width_min_m, params.street_half_width_max_m));
  w.corridor_row = ny - 1;
  w.half_width_y[w.corridor_row] = 10.0;
  const double period = params.corridor_facade_period_m;
  const auto& X = w.street_x;
  const auto& Y = w.street_y;
  const auto& hx = w.half_width_x;
  const auto& hy = w.half_width_y;

  // --- city blocks ---------------------------------------------------------------------------
  const int square_i = std::min(2, params.blocks_x - 1), square_j = 0;
  const int park_i = std::min(1, params.blocks_x - 1), park_j = std::min(2, params.blocks_y - 1);
  for (int i = 0; i + 1 < nx; ++i) {
    for (int j = 0; j + 1 < ny; ++j) {
      const double x0 = X[i] + hx[i], x1 = X[i + 1] - hx[i + 1];
      const double y0 = Y[j] + hy[j], y1 = Y[j + 1] - hy[j + 1];
      if (i == square_i && j == square_j) {  // open square: kiosk, poles, a few trees, low wall
        build.box({(x0 + x1) / 2, (y0 + y1) / 2}, {1, 0}, 5, 4, facadeSurface(rng));
        for (int k = 0; k < 6; ++k) build.pole({rng.uniform(x0 + 3, x1 - 3), rng.uniform(y0 + 3, y1 - 3)});
        for (int k = 0; k < 4; ++k) build.tree({rng.uniform(x0 + 5, x1 - 5), rng.uniform(y0 + 5, y1 - 5)});
        build.segment({x0, y1}, {x1, y1}, fenceSurface(rng));
        for (int k = 0; k < 40; ++k) build.clutter({rng.uniform(x0, x1), rng.uniform(y0, y1)});
        continue;
      }
      if (i == park_i && j == park_j) {  // park: hedged perimeter, many trees
        const Surface hedge = hedgeSurface(rng);
        for (double x = x0; x < x1 - 4; x += 12)
          if (rng.chance(0.75)) build.segment({x, y0}, {std::min(x + 10, x1), y0}, hedge);
        for (double y = y0; y < y1 - 4; y += 12)
          if (rng.chance(0.75)) build.segment({x0, y}, {x0, std::min(y + 10, y1)}, hedge);
        build.segment({x1, y0}, {x1, y1}, fenceSurface(rng));
        build.segment({x0, y1}, {x1, y1}, fenceSurface(rng));
        for (int k = 0; k < 25; ++k) build.tree({rng.uniform(x0 + 4, x1 - 4), rng.uniform(y0 + 4, y1 - 4)});
        continue;
      }
      const bool corridor_side = (j + 1 == w.corridor_row);
      if (x1 - x0 > 40 && y1 - y0 > 40)  // a courtyard building, seen through alleys
        build.box({rng.uniform(x0 + 20, x1 - 20), rng.uniform(y0 + 20, y1 - 20)}, {1, 0}, rng.uniform(8, 20),
                  rng.uniform(8, 20), facadeSurface(rng));
      build.facadeRun({x0, y0}, {x1, y0}, {0, 1});
      build.facadeRun({x0, y1}, {x1, y1}, {0, -1}, corridor_side ? period : 0.0);
      build.facadeRun({x0, y0}, {x0, y1}, {1, 0});
      build.facadeRun({x1, y0}, {x1, y1}, {-1, 0});
    }
  }
  // Outer facades across the perimeter streets (the city continues beyond the route), the
  // north one being the other side of the corridor; gaps on the east for the countryside road.
  const double xw = X[0] - hx[0], xe = X[nx - 1] + hx[nx - 1], ys = Y[0] - hy[0], yn = Y[ny - 1] + hy[ny - 1];
  build.facadeRun({xw, ys}, {xw, yn}, {-1, 0});
  build.facadeRun({xw, ys}, {xe, ys}, {0, -1});
  build.facadeRun({xw, yn}, {xe - hx[nx - 1], yn}, {0, 1}, period);
  build.facadeRun({xe, ys}, {xe, Y[1] - hy[1]}, {1, 0});
  build.facadeRun({xe, Y[1] + hy[1]}, {xe, Y[ny - 1] - hy[ny - 1]}, {1, 0});

  // --- street furniture: poles, trees, parking slots -------------------------------------------
  struct Edge {
    Vec2 a, b;
    double hw;
    bool corridor;
  };
  std::vector<Edge> edges;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
      edges.push_back({{X[i] + hx[i], Y[j]}, {X[i + 1] - hx[i + 1], Y[j]}, hy[j], j == w.corridor_row});
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j + 1 < ny; ++j)
      edges.push_back({{X[i], Y[j] + hy[j]}, {X[i], Y[j + 1] - hy[j + 1]}, hx[i], false});
  for (const Edge& e : edges) {
    const Vec2 d = unit(e.b - e.a);
    const double len = (e.b - e.a).norm();
    for (int side = -1; side <= 1; side += 2) {
      const Vec2 n = leftOf(d) * side;
      const double first = e.corridor ? std::fmod(e.a.x - xw, 2 * period) : rng.uniform(2, 10);
      const double spacing = e.corridor ? 2 * period : params.pole_spacing_m;
      for (double u = first; u < len - 2; u += spacing + (e.corridor ? 0 : rng.uniform(-6, 6)))
        build.pole(e.a + d * u + n * (e.hw - 1.2));
      if (!e.corridor && rng.chance(params.tree_probability))
        for (double u = rng.uniform(4, 12); u < len - 4; u += rng.uniform(9, 15))
          build.tree(e.a + d * u + n * (e.hw - 2.2));
      for (double u = rng.uniform(0, 4); u < len; u += rng.uniform(2, 7))
        build.clutter(e.a + d * u + n * (e.hw - rng.uniform(0.3, 4.5)));
      for (double u = 4; u < len - 6; u += 6.0) {  // parking slots; occupancy differs per traversal
        if (!trng.chance(params.parked_car_probability)) continue;
        build.box(e.a + d * (u + trng.uniform(-0.4, 0.4)) + n * (e.hw - 3.6 + trng.uniform(-0.2, 0.2)), d,
                  trng.uniform(4.0, 4.9), trng.uniform(1.7, 2.0), carSurface(trng));
      }
    }
  }

  // --- countryside loop east of the city -------------------------------------------------------
  {
    const double E = params.countryside_extent_m, xE = X[nx - 1], y1 = Y[1], yt = Y[ny - 1];
    auto jitter = [&] { return rng.uniform(-0.05, 0.05) * E; };
    w.country_road = {w.node(nx - 1, 1),
                      {xE + 0.2 * E, y1},
                      {xE + 0.5 * E + jitter(), y1 - 0.1 * E + jitter()},
                      {xE + 0.9 * E + jitter(), y1 + 0.05 * E + jitter()},
                      {xE + E + jitter(), yt - 0.3 * (yt - y1) + jitter()},
                      {xE + 0.6 * E + jitter(), yt + 0.15 * E + jitter()},
                      {xE + 0.2 * E, yt},
                      w.node(nx - 1, ny - 1)};
    const double len = polylineLength(w.country_road);
    const double city_edge = xe + 8;
    bool hedge_on[2] = {true, false};
    const Surface hedge = hedgeSurface(rng);
    for (double s = 0; s < len; s += 10) {
      Vec2 p, d;
      polylineAt(w.country_road, s, p, d);
      const Vec2 l = leftOf(d);
      for (int k = 0; k < 2; ++k) {
        const double side = k == 0 ? 1.0 : -1.0;
        if (rng.chance(0.15)) hedge_on[k] = !hedge_on[k];
        const Vec2 q = p + l * (side * rng.uniform(6.5, 8.0));
        if (hedge_on[k] && q.x > city_edge) build.segment(q, q + d * 10.0, hedge);
        if (rng.chance(0.12)) {
          const Vec2 t = p + l * (side * rng.uniform(9, 30));
          if (t.x > city_edge) build.tree(t);
        }
        for (int bush = 0; bush < 3; ++bush) {  // bushes, rocks, field edges
          const Vec2 c = p + l * (side * rng.uniform(9, 150)) + d * rng.uniform(0, 10);
          if (c.x > city_edge) build.clutter(c);
        }
      }
      if (std::fmod(s, 50.0) < 10 && p.x > city_edge) build.pole(p + l * 5.0);
      if (rng.chance(0.05) && p.x > city_edge + 30) {  // a fence line across the fields
        const Vec2 a = p + l * (rng.chance(0.5) ? 12.0 : -12.0);
        const Vec2 b = a + (a - p) * rng.uniform(2, 5);
        build.segment(a, b, fenceSurface(rng));
      }
    }
    for (int k = 0; k < 5; ++k) {  // farm buildings away from the road
      Vec2 p, d;
      polylineAt(w.country_road, rng.uniform(0.15, 0.9) * len, p, d);
      const Vec2 c = p + leftOf(d) * ((rng.chance(0.5) ? 1 : -1) * rng.uniform(30, 70));
      if (c.x > city_edge + 20) build.box(c, d, rng.uniform(15, 30), rng.uniform(8, 14), facadeSurface(rng));
    }
  }

  // --- moving vehicles on city streets (differ per traversal) ----------------------------------
  for (int k = 0; k < params.moving_vehicles && !edges.empty(); ++k) {
    const Edge& e = edges[trng.below(static_cast<std::uint32_t>(edges.size()))];
    const bool big = trng.chance(0.15);
    w.movers.push_back({e.a, e.b, trng.uniform(1.5, 2.3), trng.uniform(4, 12), trng.uniform(0, 1000),
                        big ? trng.uniform(8, 11) : trng.uniform(4.2, 4.8),
                        big ? 2.5 : trng.uniform(1.7, 1.9)});
  }

  w.buildIndex();
  return w;
}

void World::moverSegments(double t_s, Vec2 centre, double radius, double exclude_m,
                          std::vector<Segment>& out) const {
  out.clear();
  Surface s;
  s.material = Material::Car;
  s.reflectivity = 1.1f;
  s.roughness = 0.55f;
  s.transmission = 0.15f;
  s.depth_m = 0.8f;
  s.texture_period_m = 0.8f;
  for (std::size_t k = 0; k < movers.size(); ++k) {
    const Mover& m = movers[k];
    const Vec2 e = m.to - m.from;
    const double L = e.norm();
    if (L < 1) continue;
    const Vec2 d = unit(e);
    double u = std::fmod(m.phase_m + m.speed_mps * t_s, 2 * L);
    if (u < 0) u += 2 * L;
    const Vec2 dir = u < L ? d : d * -1.0;
    const Vec2 base = u < L ? m.from + d * u : m.to - d * (u - L);
    const Vec2 c = base + leftOf(dir) * m.lane_offset_m;
    const double dist = (c - centre).norm();
    if (dist > radius || dist < exclude_m) continue;
    s.texture_seed = static_cast<std::uint32_t>(k);
    const Vec2 l = leftOf(dir) * (m.width_m / 2), f = dir * (m.length_m / 2);
    const Vec2 p[4] = {c + f + l, c + f - l, c - f - l, c - f + l};
    for (int q = 0; q < 4; ++q) out.push_back({p[q], p[(q + 1) % 4], s});
  }
}

void World::buildIndex(double cell_m) {
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  auto grow = [&](Vec2 p, double r) {
    xmin = std::min(xmin, p.x - r), ymin = std::min(ymin, p.y - r);
    xmax = std::max(xmax, p.x + r), ymax = std::max(ymax, p.y + r);
  };
  for (const auto& s : segments) grow(s.a, 0), grow(s.b, 0);
  for (const auto& c : circles) grow(c.centre, c.radius);
  for (double x : street_x)
    for (double y : street_y) grow({x, y}, 0);
  for (const auto& p : country_road) grow(p, 0);
  for (const auto& p : road_points) grow(p, 0);
  const double margin = 250;  // rays start inside and may leave: the margin keeps them in
  cell_ = cell_m;
  x0_ = xmin - margin, y0_ = ymin - margin;
  nx_ = static_cast<int>(std::ceil((xmax + margin - x0_) / cell_)) + 1;
  ny_ = static_cast<int>(std::ceil((ymax + margin - y0_) / cell_)) + 1;
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(nx_) * ny_);
  auto cellOf = [&](double x, double y) {
    const int cx = std::clamp(static_cast<int>((x - x0_) / cell_), 0, nx_ - 1);
    const int cy = std::clamp(static_cast<int>((y - y0_) / cell_), 0, ny_ - 1);
    return static_cast<std::size_t>(cy) * nx_ + cx;
  };
  for (std::uint32_t k = 0; k < segments.size(); ++k) {
    const Vec2 a = segments[k].a, b = segments[k].b;
    const int steps = static_cast<int>((b - a).norm() / (cell_ * 0.25)) + 1;
    std::size_t last = static_cast<std::size_t>(-1);
    for (int q = 0; q <= steps; ++q) {
      const Vec2 p = a + (b - a) * (static_cast<double>(q) / steps);
      // the 3x3 neighbourhood guards against a segment grazing a cell corner between samples
      const std::size_t c = cellOf(p.x, p.y);
      if (c == last) continue;
      last = c;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::size_t n = cellOf(p.x + dx * cell_ * 0.3, p.y + dy * cell_ * 0.3);
          auto& v = cells[n];
          if (v.empty() || v.back() != k) v.push_back(k);
        }
    }
  }
  for (std::uint32_t k = 0; k < circles.size(); ++k) {
    const auto& c = circles[k];
    const std::size_t lo = cellOf(c.centre.x - c.radius, c.centre.y - c.radius);
    const std::size_t hi = cellOf(c.centre.x + c.radius, c.centre.y + c.radius);
    for (std::size_t cy = lo / nx_; cy <= hi / nx_; ++cy)
      for (std::size_t cx = lo % nx_; cx <= hi % nx_; ++cx) cells[cy * nx_ + cx].push_back(k | kCircleBit);
  }
  cell_start_.assign(cells.size() + 1, 0);
  cell_items_.clear();
  for (std::size_t c = 0; c < cells.size(); ++c) {
    auto& v = cells[c];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    cell_items_.insert(cell_items_.end(), v.begin(), v.end());
    cell_start_[c + 1] = static_cast<std::uint32_t>(cell_items_.size());
  }
}

RayCaster::RayCaster(const World& world)
    : world_(world), seg_mark_(world.segments.size(), 0), circ_mark_(world.circles.size(), 0) {}

namespace {
float textureAt(const Surface& s, double u) {
  const auto cell = static_cast<std::int64_t>(std::floor(u / s.texture_period_m));
  const double h = hashToUnit(hashCombine(s.texture_seed, static_cast<std::uint64_t>(cell)));
  return static_cast<float>(0.05 + 3.0 * h * h * h * h);
}

bool intersectSegment(Vec2 o, Vec2 d, const Segment& s, double max_range, RayHit& hit) {
  const Vec2 e = s.b - s.a;
  const double denom = d.cross(e);
  if (std::abs(denom) < 1e-12) return false;
  const Vec2 w = s.a - o;
  const double t = w.cross(e) / denom;
  const double u = w.cross(d) / denom;
  if (u < 0 || u > 1 || t < 0.05 || t > max_range) return false;
  const double len = e.norm();
  Vec2 n{-e.y / len, e.x / len};
  double c = d.dot(n);
  if (c > 0) n = n * -1.0, c = -c;
  hit.range = t;
  hit.cos_incidence = static_cast<float>(-c);
  hit.surface = &s.surface;
  hit.normal = n;
  hit.texture = textureAt(s.surface, u * len);
  return true;
}

bool intersectCircle(Vec2 o, Vec2 d, const Circle& c, double max_range, RayHit& hit) {
  const Vec2 oc = o - c.centre;
  const double b = oc.dot(d);
  const double q = oc.dot(oc) - c.radius * c.radius;
  const double disc = b * b - q;
  if (disc < 0) return false;
  const double t = -b - std::sqrt(disc);
  if (t < 0.05 || t > max_range) return false;
  const Vec2 p = o + d * t;
  const Vec2 n = (p - c.centre) * (1.0 / c.radius);
  hit.range = t;
  hit.cos_incidence = static_cast<float>(std::abs(d.dot(n)));
  hit.surface = &c.surface;
  hit.normal = n;
  hit.texture = textureAt(c.surface, std::atan2(n.y, n.x) * c.radius);
  return true;
}
}  // namespace

void RayCaster::cast(Vec2 o, Vec2 d, double max_range, const std::vector<Segment>& dynamic,
                     std::vector<RayHit>& hits) {
  hits.clear();
  if (++ray_id_ == 0) {
    std::fill(seg_mark_.begin(), seg_mark_.end(), 0);
    std::fill(circ_mark_.begin(), circ_mark_.end(), 0);
    ray_id_ = 1;
  }
  double opaque = max_range;
  RayHit h;
  auto consider = [&](bool ok) {
    if (!ok) return;
    hits.push_back(h);
    if (h.surface->transmission <= 0.0f) opaque = std::min(opaque, h.range);
  };
  for (const auto& s : dynamic) consider(intersectSegment(o, d, s, max_range, h));

  const World& w = world_;
  int cx = static_cast<int>(std::floor((o.x - w.x0_) / w.cell_));
  int cy = static_cast<int>(std::floor((o.y - w.y0_) / w.cell_));
  const int step_x = d.x >= 0 ? 1 : -1, step_y = d.y >= 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double dx_t = d.x != 0 ? w.cell_ / std::abs(d.x) : inf,
               dy_t = d.y != 0 ? w.cell_ / std::abs(d.y) : inf;
  double tx = d.x != 0 ? ((w.x0_ + (cx + (step_x > 0 ? 1 : 0)) * w.cell_) - o.x) / d.x : inf;
  double ty = d.y != 0 ? ((w.y0_ + (cy + (step_y > 0 ? 1 : 0)) * w.cell_) - o.y) / d.y : inf;
  while (cx >= 0 && cy >= 0 && cx < w.nx_ && cy < w.ny_) {
    const std::size_t c = static_cast<std::size_t>(cy) * w.nx_ + cx;
    for (std::uint32_t k = w.cell_start_[c]; k < w.cell_start_[c + 1]; ++k) {
      const std::uint32_t item = w.cell_items_[k];
      if (item & kCircleBit) {
        const std::uint32_t i = item & ~kCircleBit;
        if (circ_mark_[i] == ray_id_) continue;
        circ_mark_[i] = ray_id_;
        consider(intersectCircle(o, d, w.circles[i], opaque, h));
      } else {
        if (seg_mark_[item] == ray_id_) continue;
        seg_mark_[item] = ray_id_;
        consider(intersectSegment(o, d, w.segments[item], opaque, h));
      }
    }
    const double t_exit = std::min(tx, ty);
    if (t_exit >= opaque) break;
    if (tx < ty)
      tx += dx_t, cx += step_x;
    else
      ty += dy_t, cy += step_y;
  }
  std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.range < b.range; });
  double through = 1.0;
  for (std::size_t k = 0; k < hits.size(); ++k) {
    through *= hits[k].surface->transmission;
    if (through < 1e-3) {
      hits.resize(k + 1);
      break;
    }
  }
}

}  // namespace radarslam::sim
