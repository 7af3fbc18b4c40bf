#pragma once
// Shared helpers for the simulator tests: a small, fast radar geometry; a route sampled in time.
#include "radarslam/core/trajectory.h"
#include "radarslam/sim/route.h"
#include "radarslam/sim/simulator.h"

namespace radarslam::sim::simtest {

/// 100 azimuths x 600 bins x 0.2 m (120 m) at 4 Hz: ~25x fewer bins than Oxford, same physics.
inline SimulationConfig smallConfig(std::uint64_t seed = 1, int scans = 4) {
  SimulationConfig c;
  c.seed = seed;
  c.scans = scans;
  c.geometry.azimuths = 100;
  c.geometry.bins = 600;
  c.geometry.range_resolution_m = 0.2;
  return c;
}

/// The route's pose every `dt_s` seconds from its start to its end.
inline Trajectory sampleTrajectory(const Route& r, double dt_s) {
  Trajectory t;
  for (double s = 0; s < r.duration(); s += dt_s) {
    const StampNs stamp = r.start_stamp + static_cast<StampNs>(s * 1e9);
    t.push_back({stamp, r.poseAt(stamp)});
  }
  return t;
}

}  // namespace radarslam::sim::simtest
