#include "clear_placer.h"

#include <algorithm>
#include <cmath>

#include "world_builder.h"

namespace radarslam::sim::detail {

void ClearPlacer::segment(Vec2 a, Vec2 b, const Surface& s) {
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / 0.5)));
  int run_start = -1;
  for (int k = 0; k <= n + 1; ++k) {
    const bool ok = k <= n && clear(a + (b - a) * (static_cast<double>(k) / n));
    if (ok && run_start < 0) run_start = k;
    if (!ok && run_start >= 0) {
      if (k - 1 > run_start)
        w_.segments.push_back({a + (b - a) * (static_cast<double>(run_start) / n),
                               a + (b - a) * (static_cast<double>(k - 1) / n), s});
      run_start = -1;
    }
  }
}

void ClearPlacer::circle(Vec2 c, double r, const Surface& s) {
  if (clear(c, r)) w_.circles.push_back({c, r, s});
}

void ClearPlacer::box(Vec2 c, Vec2 dir, double length, double width, const Surface& s, bool whole) {
  const Vec2 l = leftOf(dir) * (width / 2), f = dir * (length / 2);
  const Vec2 q[4] = {c + f + l, c + f - l, c - f - l, c - f + l};
  if (whole) {
    for (int k = 0; k < 4; ++k) {
      const Vec2 e = q[(k + 1) % 4] - q[k];
      const int n = std::max(1, static_cast<int>(std::ceil(e.norm() / 0.5)));
      for (int t = 0; t < n; ++t)
        if (!clear(q[k] + e * (static_cast<double>(t) / n))) return;
    }
    for (int k = 0; k < 4; ++k) w_.segments.push_back({q[k], q[(k + 1) % 4], s});
    return;
  }
  for (int k = 0; k < 4; ++k) segment(q[k], q[(k + 1) % 4], s);
}

void ClearPlacer::tree(Vec2 c, Rng& rng) {
  const double r = rng.uniform(1.5, 3.0);
  const Surface canopy = canopySurface(rng);
  Surface trunk = poleSurface(rng);
  trunk.reflectivity = 0.5f;
  trunk.roughness = 0.8f;
  const double tr = rng.uniform(0.15, 0.3);
  if (!clear(c, r)) return;
  w_.circles.push_back({c, r, canopy});
  w_.circles.push_back({c, tr, trunk});
}

void ClearPlacer::pole(Vec2 c, Rng& rng) {
  const double r = rng.uniform(0.1, 0.2);
  circle(c, r, poleSurface(rng));
}

void ClearPlacer::clutter(Vec2 c, Rng& rng) {
  const Surface s = clutterSurface(rng);
  circle(c, rng.uniform(0.1, 0.4), s);
}

}  // namespace radarslam::sim::detail
