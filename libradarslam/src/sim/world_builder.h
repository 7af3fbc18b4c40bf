#pragma once
// Private to the simulator's world generators (world.cpp, route_world.cpp): the surfaces of each
// material with their random spread, and a Builder that adds boxes, poles, trees and facade runs
// to a World. Every helper draws from the Rng it is given, in a fixed order.
#include <algorithm>
#include <cmath>

#include "radarslam/sim/rng.h"
#include "radarslam/sim/world.h"

namespace radarslam::sim::detail {

// The world frame follows the Oxford SDK convention (z down, +y to the right of +x), so the
// left of a travel direction d is (d.y, -d.x).
inline Vec2 leftOf(Vec2 d) { return {d.y, -d.x}; }

inline Vec2 unit(Vec2 v) {
  const double n = v.norm();
  return n > 0 ? v * (1.0 / n) : Vec2{1, 0};
}

inline Surface facadeSurface(Rng& rng) {
  Surface s;
  s.material = Material::Facade;
  s.reflectivity = static_cast<float>(rng.uniform(0.35, 1.0));
  s.roughness = static_cast<float>(rng.uniform(0.1, 0.6));
  // The fan beam (~40 deg vertically) sees partly over low buildings and roofs.
  s.transmission = rng.chance(0.4) ? 0.15f : 0.04f;
  s.depth_m = static_cast<float>(rng.uniform(0.05, 0.5));
  s.texture_period_m = static_cast<float>(rng.uniform(1.0, 3.5));
  s.texture_seed = static_cast<std::uint32_t>(rng.next());
  return s;
}

/// A material with one random parameter, its reflectivity in [reflectivity_lo, reflectivity_hi);
/// drawn in a fixed order (reflectivity, then the texture seed) so worlds stay reproducible.
struct MaterialSpec {
  Material material;
  double reflectivity_lo, reflectivity_hi;
  float roughness, transmission, depth_m, texture_period_m;
};

inline Surface drawSurface(const MaterialSpec& m, Rng& rng) {
  Surface s;
  s.material = m.material;
  s.reflectivity = static_cast<float>(rng.uniform(m.reflectivity_lo, m.reflectivity_hi));
  s.roughness = m.roughness;
  s.transmission = m.transmission;
  s.depth_m = m.depth_m;
  s.texture_period_m = m.texture_period_m;
  s.texture_seed = static_cast<std::uint32_t>(rng.next());
  return s;
}

// The beam partly passes under and around a car.
inline Surface carSurface(Rng& rng) {
  return drawSurface({Material::Car, 0.8, 1.4, 0.55f, 0.15f, 0.8f, 0.8f}, rng);
}
inline Surface poleSurface(Rng& rng) {
  return drawSurface({Material::Pole, 1.0, 2.0, 0.3f, 0.0f, 0.2f, 10.0f}, rng);
}
inline Surface canopySurface(Rng& rng) {
  return drawSurface({Material::Tree, 0.15, 0.35, 1.0f, 0.55f, 2.0f, 0.7f}, rng);
}
inline Surface hedgeSurface(Rng& rng) {
  return drawSurface({Material::Hedge, 0.2, 0.4, 1.0f, 0.3f, 1.5f, 0.8f}, rng);
}
// Fence texture: the posts.
inline Surface fenceSurface(Rng& rng) {
  return drawSurface({Material::Fence, 0.25, 0.5, 0.8f, 0.6f, 0.2f, 2.5f}, rng);
}
/// Small street clutter: bins, bollards, signs, bikes, bushes.
inline Surface clutterSurface(Rng& rng) {
  return drawSurface({Material::Pole, 0.1, 0.9, 0.8f, 0.5f, 0.3f, 1.0f}, rng);
}

class Builder {
 public:
  Builder(World& w, Rng& rng) : w_(w), rng_(rng) {}

  void segment(Vec2 a, Vec2 b, const Surface& s) { w_.segments.push_back({a, b, s}); }

  void box(Vec2 c, Vec2 dir, double length, double width, const Surface& s) {
    const Vec2 l = leftOf(dir) * (width / 2), f = dir * (length / 2);
    const Vec2 p[4] = {c + f + l, c + f - l, c - f - l, c - f + l};
    for (int k = 0; k < 4; ++k) segment(p[k], p[(k + 1) % 4], s);
  }

  void pole(Vec2 c) { w_.circles.push_back({c, rng_.uniform(0.1, 0.2), poleSurface(rng_)}); }

  void clutter(Vec2 c) {
    const Surface s = clutterSurface(rng_);
    w_.circles.push_back({c, rng_.uniform(0.1, 0.4), s});
  }

  void tree(Vec2 c) {
    w_.circles.push_back({c, rng_.uniform(1.5, 3.0), canopySurface(rng_)});
    Surface trunk = poleSurface(rng_);
    trunk.reflectivity = 0.5f;
    trunk.roughness = 0.8f;
    w_.circles.push_back({c, rng_.uniform(0.15, 0.3), trunk});
  }

  /// A run of building facades from a to b; `inward` points into the block. Buildings of random
  /// width (or of exactly `period` for identical terraces) with setbacks and occasional alleys.
  void facadeRun(Vec2 a, Vec2 b, Vec2 inward, double period = 0) {
    const Vec2 e = b - a;
    const double len = e.norm();
    const Vec2 d = unit(e);
    Surface terrace;
    if (period > 0) {
      Rng trng(hashCombine(w_.seed, 0xC0441D02));
      terrace = facadeSurface(trng);
      terrace.texture_period_m = static_cast<float>(period / 6.0);
    }
    double u = 0, prev_setback = 0;
    bool have_prev = false;
    while (u < len - 1.0) {
      const double width = std::min(len - u, period > 0 ? period : rng_.uniform(8, 30));
      if (period <= 0 && have_prev && rng_.chance(0.22)) {  // an alley or a gap between buildings
        u += rng_.uniform(3.0, 8.0);
        have_prev = false;
        continue;
      }
      const double setback = period > 0 ? 0.0 : rng_.uniform(0.0, 1.5);
      const Vec2 p0 = a + d * u + inward * setback, p1 = a + d * (u + width) + inward * setback;
      const Surface s = period > 0 ? terrace : facadeSurface(rng_);
      segment(p0, p1, s);
      if (have_prev && std::abs(setback - prev_setback) > 0.05)
        segment(a + d * u + inward * prev_setback, p0, s);
      if (period <= 0) {  // the building's side walls, visible through alleys
        segment(p0, p0 + inward * rng_.uniform(8, 15), s);
        segment(p1, p1 + inward * rng_.uniform(8, 15), s);
      }
      prev_setback = setback;
      have_prev = true;
      u += width;
    }
  }

 private:
  World& w_;
  Rng& rng_;
};

}  // namespace radarslam::sim::detail
