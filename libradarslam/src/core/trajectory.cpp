#include "radarslam/core/trajectory.h"

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

#include "radarslam/core/errors.h"

namespace radarslam {

std::optional<mrpt::math::TPose2D> interpolatePose(const Trajectory& traj, StampNs t, StampNs max_gap_ns) {
  if (traj.empty() || t < traj.front().stamp || t > traj.back().stamp) return std::nullopt;
  const auto hi = std::lower_bound(traj.begin(), traj.end(), t,
                                   [](const StampedPose& p, StampNs s) { return p.stamp < s; });
  if (hi->stamp == t) return hi->pose;
  const auto lo = hi - 1;
  if (hi->stamp - lo->stamp > max_gap_ns) return std::nullopt;
  const double a = static_cast<double>(t - lo->stamp) / static_cast<double>(hi->stamp - lo->stamp);
  const auto& p = lo->pose;
  const auto& q = hi->pose;
  return mrpt::math::TPose2D(p.x + a * (q.x - p.x), p.y + a * (q.y - p.y),
                             mrpt::math::wrapToPi(p.phi + a * mrpt::math::wrapToPi(q.phi - p.phi)));
}

double pathLength(const Trajectory& traj) {
  double len = 0.0;
  for (std::size_t i = 1; i < traj.size(); ++i)
    len += std::hypot(traj[i].pose.x - traj[i - 1].pose.x, traj[i].pose.y - traj[i - 1].pose.y);
  return len;
}

std::optional<std::size_t> firstImplausiblePose(const Trajectory& traj) {
  for (std::size_t i = 0; i < traj.size(); ++i) {
    const auto& p = traj[i].pose;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.phi) ||
        std::abs(p.x) > kMaxCoordinateM || std::abs(p.y) > kMaxCoordinateM)
      return i;
  }
  return std::nullopt;
}

void checkPlausiblePoses(const Trajectory& traj, const std::string& where) {
  if (const auto i = firstImplausiblePose(traj))
    throw InputError(where, "pose " + std::to_string(*i + 1) + " (" + std::to_string(traj[*i].pose.x) + ", " +
                                std::to_string(traj[*i].pose.y) +
                                ") is not finite or farther than 1e7 m from the origin");
}

std::optional<std::size_t> firstNonIncreasingStamp(const Trajectory& traj) {
  for (std::size_t i = 1; i < traj.size(); ++i)
    if (traj[i].stamp <= traj[i - 1].stamp) return i;
  return std::nullopt;
}

}  // namespace radarslam
