#pragma once
// Local mapping (paper Sec. III-B) for one new keyframe: its peak cloud (Algorithm 1, motion
// compensated) and M2DP descriptor for loop closing, map points from the tracker's measurements
// (each of the previous keyframe's keypoints the tracker measured in the new keyframe becomes
// another observation of that keypoint's map point, at the measured position), local bundle
// adjustment over the newest keyframes, and culling of map points seen by too few keyframes once
// they leave the window.
#include <memory>
#include <utility>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"
#include "radarslam/radar/motion_compensation.h"
#include "slam_state.h"

namespace radarslam::slam_detail {

/// What tracking hands to local mapping for each new keyframe.
struct KeyframeJob {
  std::uint64_t id = 0;
  StampNs stamp = 0;
  TPose2D odom_pose;
  bool lost = false;
  double travelled_m = 0;
  BodyVelocity velocity;
  std::vector<Eigen::Vector2d> keypoints;
  std::vector<Eigen::Matrix2d> structure;         ///< OdometryStep::keyframe_structure
  std::vector<KeyframeObservation> observations;  ///< OdometryStep::keyframe_observations
  std::shared_ptr<const CObservationRadarScan> scan;
  // Filled by LocalMapper::describe() (threaded: in a stage of its own, before insert()).
  std::shared_ptr<const std::vector<RadarPoint>> cloud;
  M2DPDescriptor descriptor, descriptor_flipped;
  double describe_ms = 0;
};

class LocalMapper {
 public:
  LocalMapper(SlamState& state, const SlamParams& params) : state_(state), params_(params) {}
  /// The keyframe's peak cloud (Algorithm 1) moved to the scan's reference time, and its M2DP
  /// descriptors (both signs of the PCA axis, see loop/m2dp.h). Touches no shared state: the
  /// threaded pipeline runs it in a stage of its own, one keyframe ahead of insert().
  void describe(KeyframeJob& job) const;
  /// Inserts the keyframe (ids arrive in order 0, 1, 2, ...; described first if it was not) and
  /// runs the local BA.
  void insert(const KeyframeJob& job);

 private:
  void associate(SlamKeyframe& kf, const KeyframeJob& job);
  void bundleAdjust(std::uint64_t newest);
  void retire(std::uint64_t id);
  SlamState& state_;
  const SlamParams& params_;
};

}  // namespace radarslam::slam_detail
