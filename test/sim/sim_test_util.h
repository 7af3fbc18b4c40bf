#pragma once
// Shared helpers for the simulator tests: a small, fast radar geometry.
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

}  // namespace radarslam::sim::simtest
