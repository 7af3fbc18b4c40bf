#pragma once
// A synthetic 2D world for the localisation tests: random wall segments and point scatterers, seen
// by a 360-degree "radar" as noisy points (sensor frame) within a range, with random dropout.
#include <mrpt/math/TPose2D.h>
#include <mrpt/poses/CPose2D.h>

#include <cmath>
#include <random>
#include <vector>

#include "radarslam/map/keyframe_map.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam::test {

struct SyntheticWorld {
  std::vector<std::pair<double, double>> points;  ///< world frame

  /// Walls along a corridor of streets around the path y = 0, x in [x0, x1], plus scatterers.
  static SyntheticWorld make(unsigned seed, double x0 = -100, double x1 = 400) {
    SyntheticWorld w;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (double x = x0; x < x1;) {  // building facades on both sides, random lengths and setbacks
      const double len = 5 + 25 * u(rng), gap = 2 + 10 * u(rng);
      for (int side = -1; side <= 1; side += 2) {
        const double y = side * (8 + 12 * u(rng));
        const double ang = (u(rng) - 0.5) * 0.3;
        for (double t = 0; t < len; t += 0.3)
          w.points.emplace_back(x + t * std::cos(ang), y + t * std::sin(ang));
        // a side wall going away from the street
        const double side_len = 3 + 10 * u(rng);
        for (double t = 0; t < side_len; t += 0.3) w.points.emplace_back(x, y + side * t);
      }
      x += len + gap;
    }
    for (int i = 0; i < 400; ++i)  // poles, cars, trees
      w.points.emplace_back(x0 + (x1 - x0) * u(rng), (u(rng) - 0.5) * 70);
    return w;
  }

  /// The world points within `range` of `pose`, in its sensor frame, with Gaussian noise `sigma`
  /// and each point dropped with probability `dropout`.
  std::vector<RadarPoint> scan(const mrpt::math::TPose2D& pose, unsigned seed, double sigma = 0.05,
                               double dropout = 0.2, double range = 80) const {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, sigma);
    std::uniform_real_distribution<double> u(0, 1);
    const mrpt::poses::CPose2D inv = -mrpt::poses::CPose2D(pose);
    std::vector<RadarPoint> out;
    for (const auto& [x, y] : points) {
      if (std::hypot(x - pose.x, y - pose.y) > range || u(rng) < dropout) continue;
      double lx = 0, ly = 0;
      inv.composePoint(x, y, lx, ly);
      RadarPoint p;
      p.x = static_cast<float>(lx + n(rng));
      p.y = static_cast<float>(ly + n(rng));
      p.range_m = std::hypot(p.x, p.y);
      p.power = static_cast<float>(60 + 150 * u(rng));
      out.push_back(p);
    }
    return out;
  }

  /// A map with a keyframe every `step` metres along y = 0 from x = 0 to `length`.
  KeyframeMap map(double length = 300, double step = 2, unsigned seed = 1000) const {
    KeyframeMap m;
    for (double x = 0; x <= length; x += step) {
      Keyframe kf;
      kf.id = m.keyframes.size();
      kf.stamp_ns = static_cast<StampNs>(kf.id) * 250'000'000;
      kf.pose = {x, 0.0, 0.0};
      for (const auto& p : scan(kf.pose, seed + static_cast<unsigned>(kf.id)))
        kf.points.push_back({p.x, p.y, p.power});
      m.keyframes.push_back(std::move(kf));
    }
    return m;
  }
};

}  // namespace radarslam::test
