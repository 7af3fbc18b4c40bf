#pragma once
// Stamped SE(2) trajectories: ground truth and estimates alike. Poses are absolute radar poses
// in a fixed world frame at each stamp (radarslam's single ground-truth convention).
#include <mrpt/math/TPose2D.h>

#include <optional>
#include <string>
#include <vector>

#include "radarslam/core/time.h"

namespace radarslam {

struct StampedPose {
  StampNs stamp = 0;
  mrpt::math::TPose2D pose;
};

using Trajectory = std::vector<StampedPose>;

/// Pose at time t by interpolation between the two neighbouring samples (linear in x, y and along
/// the shorter arc in yaw). nullopt if t is outside the trajectory's time span or the two
/// neighbours are more than `max_gap_ns` apart. Requires stamps strictly increasing.
std::optional<mrpt::math::TPose2D> interpolatePose(const Trajectory& traj, StampNs t,
                                                   StampNs max_gap_ns = 2 * kNsPerSec);

/// Sum of the distances between consecutive positions, metres.
double pathLength(const Trajectory& traj);

/// Largest |x| or |y| a pose may have, in metres: 10 000 km covers every planar frame in use
/// (UTM northings included). Farther coordinates are corrupt data, refused by the trajectory
/// readers and the evaluation before any path length, grid or plot is computed from them.
inline constexpr double kMaxCoordinateM = 1e7;

/// Index of the first pose that is not finite or farther than kMaxCoordinateM, or nullopt.
std::optional<std::size_t> firstImplausiblePose(const Trajectory& traj);
/// Throws InputError(where, "pose N ...") if firstImplausiblePose() finds one.
void checkPlausiblePoses(const Trajectory& traj, const std::string& where);

/// Index of the first sample whose stamp does not increase, or nullopt if strictly increasing.
std::optional<std::size_t> firstNonIncreasingStamp(const Trajectory& traj);

}  // namespace radarslam
