#pragma once
// Hand-built trajectories for the evaluation tests.
#include <mrpt/math/TPose2D.h>

#include <cmath>
#include <vector>

#include "radarslam/core/trajectory.h"

namespace radarslam::test {

/// A straight drive along +x: `n` poses `spacing` metres apart, stamped `dt_ns` apart from t0.
inline Trajectory straightLine(std::size_t n, double spacing, StampNs dt_ns = 250'000'000, StampNs t0 = 0) {
  Trajectory t;
  for (std::size_t k = 0; k < n; ++k)
    t.push_back(
        {t0 + static_cast<StampNs>(k) * dt_ns, mrpt::math::TPose2D(static_cast<double>(k) * spacing, 0, 0)});
  return t;
}

/// Chains relative motions: pose[k+1] = pose[k] (+) step(k), as odometry does.
template <typename Step>
Trajectory chain(std::size_t n, Step&& step, StampNs dt_ns = 250'000'000, mrpt::math::TPose2D start = {}) {
  Trajectory t{{0, start}};
  for (std::size_t k = 1; k < n; ++k)
    t.push_back({static_cast<StampNs>(k) * dt_ns, t.back().pose + step(k - 1)});
  return t;
}

/// A winding drive: speed 8 m/s, yaw rate varying smoothly; 4 Hz.
inline Trajectory windingDrive(std::size_t n) {
  return chain(n, [](std::size_t k) {
    return mrpt::math::TPose2D(2.0, 0.0, 0.05 * std::sin(0.013 * static_cast<double>(k)));
  });
}

inline std::vector<mrpt::math::TPose2D> posesOf(const Trajectory& t) {
  std::vector<mrpt::math::TPose2D> p;
  for (const auto& s : t) p.push_back(s.pose);
  return p;
}

/// Every pose moved by the rigid transform T (a change of world frame): T (+) pose.
inline Trajectory transformed(const Trajectory& t, const mrpt::math::TPose2D& T) {
  Trajectory out = t;
  for (auto& s : out) s.pose = T + s.pose;
  return out;
}

/// Positions scaled by `s` about the origin, headings kept (a pure odometry scale error).
inline Trajectory scaled(const Trajectory& t, double s) {
  Trajectory out = t;
  for (auto& p : out) p.pose.x *= s, p.pose.y *= s;
  return out;
}

}  // namespace radarslam::test
