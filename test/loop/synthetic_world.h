#pragma once
// Synthetic 2D point worlds for the loop-closure tests: random structured scenes (building walls
// and poles) and a corridor of identical facades, observed by an idealised 360-degree scanner
// (points resampled along walls per scan, range noise, dropout, no occlusion).
#include <cmath>
#include <random>
#include <vector>

#include "radarslam/radar/peak_cloud.h"

namespace radarslam::looptest {

struct Wall {
  double ax, ay, bx, by;
  float power;
};

struct PointWorld {
  std::vector<Wall> walls;  // poles are zero-length walls
};

/// Random blocks of buildings (axis-aligned rectangles with gaps) and poles over +-extent metres.
inline PointWorld randomWorld(unsigned seed, double extent = 300) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-extent, extent), size(6, 30), power(60, 250), u(0, 1);
  PointWorld w;
  for (int i = 0; i < static_cast<int>(extent * extent / 900); ++i) {
    const double x = pos(rng), y = pos(rng), sx = size(rng), sy = size(rng);
    const double c[5][2] = {{x, y}, {x + sx, y}, {x + sx, y + sy}, {x, y + sy}, {x, y}};
    for (int k = 0; k < 4; ++k)
      if (u(rng) < 0.8)
        w.walls.push_back({c[k][0], c[k][1], c[k + 1][0], c[k + 1][1], static_cast<float>(power(rng))});
  }
  for (int i = 0; i < static_cast<int>(extent * extent / 300); ++i) {
    const double x = pos(rng), y = pos(rng);
    w.walls.push_back({x, y, x, y, static_cast<float>(power(rng))});
  }
  return w;
}

/// Two facade rows (y = +-12 m) repeating every `period` metres in x over [-length, length]: each
/// period has a house front, a recess and a lamp post, identical everywhere.
inline PointWorld corridorWorld(double period = 12, double length = 400) {
  PointWorld w;
  for (double x0 = -length; x0 < length; x0 += period) {
    for (double side : {-1.0, 1.0}) {
      const double y = 12 * side;
      w.walls.push_back({x0, y, x0 + 0.7 * period, y, 180.f});
      w.walls.push_back({x0 + 0.7 * period, y, x0 + 0.7 * period, y + 2 * side, 120.f});
      w.walls.push_back({x0 + 0.7 * period, y + 2 * side, x0 + period, y + 2 * side, 150.f});
      w.walls.push_back({x0 + period, y + 2 * side, x0 + period, y, 120.f});
      w.walls.push_back({x0 + 0.3 * period, y - 3 * side, x0 + 0.3 * period, y - 3 * side, 220.f});
    }
  }
  return w;
}

/// A scan from sensor pose (x, y, yaw): wall points resampled every ~1/density m with a random
/// phase, range noise sigma, dropout probability, within max_range; in the sensor frame.
inline std::vector<RadarPoint> observe(const PointWorld& w, double x, double y, double yaw, unsigned seed,
                                       double max_range = 80, double density = 1.5, double sigma = 0.05,
                                       double dropout = 0.1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> noise(0, sigma);
  std::vector<RadarPoint> out;
  const double c = std::cos(yaw), s = std::sin(yaw);
  auto emit = [&](double px, double py, float power) {
    const double dx = px - x, dy = py - y;
    if (dx * dx + dy * dy > max_range * max_range || dx * dx + dy * dy < 4) return;
    if (u(rng) < dropout) return;
    RadarPoint p;
    p.x = static_cast<float>(c * dx + s * dy + noise(rng));
    p.y = static_cast<float>(-s * dx + c * dy + noise(rng));
    p.range_m = std::hypot(p.x, p.y);
    p.power = power;
    out.push_back(p);
  };
  for (const auto& wl : w.walls) {
    const double len = std::hypot(wl.bx - wl.ax, wl.by - wl.ay);
    if (len < 1e-9) {
      emit(wl.ax, wl.ay, wl.power);
      continue;
    }
    const double step = 1.0 / density;
    for (double t = u(rng) * step; t < len; t += step)
      emit(wl.ax + (wl.bx - wl.ax) * t / len, wl.ay + (wl.by - wl.ay) * t / len, wl.power);
  }
  return out;
}

/// The cloud moved rigidly: p' = R(yaw) p + (tx, ty).
inline std::vector<RadarPoint> transformed(std::vector<RadarPoint> cloud, double tx, double ty, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (auto& p : cloud) {
    const double x = p.x, y = p.y;
    p.x = static_cast<float>(c * x - s * y + tx);
    p.y = static_cast<float>(s * x + c * y + ty);
  }
  return cloud;
}

}  // namespace radarslam::looptest
