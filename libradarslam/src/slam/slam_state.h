#pragma once
// The state the SLAM threads share (keyframes, map points, accepted loops), guarded by one
// mutex. Keyframe ids are indices into `keyframes`. Private to the slam module.
#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "radarslam/core/time.h"
#include "radarslam/loop/m2dp.h"
#include "radarslam/radar/peak_cloud.h"
#include "radarslam/slam/radar_slam.h"

namespace radarslam::slam_detail {

using mrpt::math::TPose2D;

/// a (+) b
inline TPose2D compose(const TPose2D& a, const TPose2D& b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, std::remainder(a.phi + b.phi, 2 * M_PI)};
}
/// a^-1 (+) b: b in the frame of a
inline TPose2D between(const TPose2D& a, const TPose2D& b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi), dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, std::remainder(b.phi - a.phi, 2 * M_PI)};
}
inline Eigen::Vector2d transformPoint(const TPose2D& a, const Eigen::Vector2d& p) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  return {a.x + c * p.x() - s * p.y(), a.y + s * p.x() + c * p.y()};
}
/// `error` without its component along a partial loop's line (LoopRecord::slide): `direction` is a
/// unit vector in the query's frame, the query at heading `phi` in the frame of `error`.
inline Eigen::Vector2d acrossLine(const Eigen::Vector2d& error, const Eigen::Vector2d& direction,
                                  double phi) {
  const Eigen::Vector2d u = transformPoint(TPose2D(0, 0, phi), direction);
  return error - error.dot(u) * u;
}
inline Eigen::Vector2d inverseTransformPoint(const TPose2D& a, const Eigen::Vector2d& p) {
  const double c = std::cos(a.phi), s = std::sin(a.phi), dx = p.x() - a.x, dy = p.y() - a.y;
  return {c * dx + s * dy, -s * dx + c * dy};
}

struct SlamKeyframe {
  std::uint64_t id = 0;
  StampNs stamp = 0;
  TPose2D pose;                ///< map frame, current estimate
  TPose2D odom_pose;           ///< the tracker's (odometry) frame
  TPose2D odom_edge;           ///< measured pose relative to the previous keyframe (refined by local BA)
  TPose2D tracked_edge;        ///< the same as the odometry tracked it, never refined: local BA's prior
  bool lost = false;           ///< created by a tracking loss: odom_edge is a prediction
  bool session_start = false;  ///< first keyframe of a session: no odometry edge to the previous one
  double travelled_m = 0;
  std::shared_ptr<const std::vector<RadarPoint>> cloud;  ///< peak cloud, sensor frame, compensated
  M2DPDescriptor descriptor, descriptor_flipped;
  // Local mapping's association data, kept while the keyframe is in the BA window.
  std::vector<Eigen::Vector2d> keypoints;
  std::vector<Eigen::Matrix2d> keypoint_structure;  ///< information shape per keypoint (empty: isotropic)
  std::vector<std::int64_t> keypoint_point;         ///< map point index per keypoint, or -1
  /// Per keypoint of an existing map point: that point's observation here minus the keypoint (the
  /// detector's position of the landmark differs from where the point's first patch was measured);
  /// the next keyframe's measurement of this keypoint is shifted by it, so a point's observations
  /// all locate the same patch.
  std::vector<Eigen::Vector2d> keypoint_offset;
};

struct SlamMapPoint {
  Eigen::Vector2d xy;           ///< map frame
  std::uint64_t reference = 0;  ///< keyframe that first saw it: loop corrections move it with that one
  /// 32 bytes (z is 16-byte aligned): the keyframe id in 32 bits and the shape fill the 16 before z.
  struct Observation {
    Observation(std::uint64_t keyframe_id, const Eigen::Vector2d& z_sensor,
                const std::array<float, 3>& shape_xx_xy_yy = {1.0f, 0.0f, 1.0f})
        : keyframe(static_cast<std::uint32_t>(keyframe_id)), shape(shape_xx_xy_yy), z(z_sensor) {}
    std::uint32_t keyframe;  ///< 2^32 keyframes would be 34 years of scans at 4 Hz
    /// z's information shape (frontend/structure_information.h): xx, xy, yy; isotropic by default.
    std::array<float, 3> shape;
    Eigen::Vector2d z;  ///< sensor frame
  };
  static_assert(sizeof(Observation) == 32);
  std::vector<Observation> observations;
  bool culled = false;
};

struct AcceptedLoop {
  std::uint64_t from = 0, to = 0;  ///< match (older), query
  TPose2D relative;                ///< `to` in the frame of `from`
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  static constexpr std::size_t kNoRecord = static_cast<std::size_t>(-1);
  std::size_t record = kNoRecord;  ///< index into records (kNoRecord: a loop of a loaded map)
  bool active = true;
};

struct SlamState {
  mutable std::mutex mutex;
  std::vector<SlamKeyframe> keyframes;
  std::vector<SlamMapPoint> points;
  std::vector<AcceptedLoop> loops;
  std::vector<LoopRecord> records;
  std::uint64_t corrections = 0;  ///< bumped by every pose-graph correction (invalidates a running BA)
  /// Extending a loaded map: keyframes [0, session_first) are the map's. The new session's poses
  /// are in its own odometry frame until loop closing anchors it to the map (anchored = true).
  std::uint64_t session_first = 0;
  bool anchored = true;
  /// The odometry edges' covariance (OdometryEdgeParams) times this: estimated from the verified
  /// loops (DriftScaleEstimator, slam/loop_uncertainty.h) so that odometry that drifts more than the
  /// parameters say gets the uncertainty it has, in the drift gate and in the pose graph.
  double odometry_variance_scale = 1.0;
  std::uint64_t anchor_keyframe = 0;  ///< the new session's keyframe whose loop anchored it
  double anchor_travelled_m = 0;      ///< the anchoring keyframe's travelled_m (drift bound to map keyframes)
  SlamStats stats;
};

}  // namespace radarslam::slam_detail
