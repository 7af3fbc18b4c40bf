#pragma once
// How a trajectory turns: the distribution of its yaw rate and yaw acceleration, from the poses
// at consecutive scan times. The simulator's realism check compares a simulated route's figures
// with a real drive's ground truth (docs/simulator.md, "the simulated vehicle turns like a car").
#include "radarslam/core/trajectory.h"

namespace radarslam::eval {

struct YawDynamics {
  std::size_t samples = 0;  ///< yaw-acceleration samples (poses - 2)
  double rate_p99_dps = 0, rate_max_dps = 0;
  double accel_p95_dps2 = 0, accel_p99_dps2 = 0, accel_max_dps2 = 0;
};

/// |yaw rate| between consecutive poses and |its change| between consecutive pairs (per second,
/// at the pairs' mid times). Throws std::invalid_argument for fewer than 3 poses or stamps that
/// do not increase.
YawDynamics yawDynamics(const Trajectory& poses);

}  // namespace radarslam::eval
