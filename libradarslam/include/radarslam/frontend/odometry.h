#pragma once
// RadarSLAM pose tracking (paper Sec. III-A): keyframe-based radar odometry.
//   scan -> Cartesian image -> keypoints + descriptors -> motion compensation (ours) ->
//   matching within a motion-prior radius -> consistency graph (eq. (3)) -> maximum clique ->
//   SVD pose -> refinement against the keyframe's points (eq. (4)) -> C_t = C_k T_tk^-1 (eq. (2))
//   -> keyframe decision.
// A scan that cannot be tracked never aborts the run: its pose is predicted with constant
// velocity and it becomes the new keyframe (re-initialisation) - unless it has too few keypoints
// to track against (a blank scan), in which case the old keyframe is kept for up to
// tracking.keep_keyframe_when_lost scans. The search radius comes from the prediction's running
// error (frontend/motion_prior_bound.h) and widens with the scans lost since the last estimate;
// the wide initial radius is used only without a velocity (start, data gap).
#include <Eigen/Core>

#include <memory>
#include <utility>
#include <vector>

#include "radarslam/core/trajectory.h"
#include "radarslam/frontend/motion_compensation.h"
#include "radarslam/frontend/odometry_params.h"
#include "radarslam/frontend/radius_matcher.h"

namespace radarslam {

enum class TrackingStatus { Initialised, Tracking, Lost, Recovered };
const char* toString(TrackingStatus s);

/// Wall time of each stage of one scan, milliseconds. `align_prep` smooths the image for patch
/// alignment (and, for a new keyframe, computes its points' structure shapes); `refine` includes
/// the patch alignment of matches and keyframe points and eq. (4).
struct StageTimes {
  double cartesian = 0, detect = 0, describe = 0, align_prep = 0, match = 0, clique = 0, svd = 0, refine = 0;
  double total() const { return cartesian + detect + describe + align_prep + match + clique + svd + refine; }
};

/// One of the previous keyframe's keypoints as the final pose estimate measured it in the new
/// keyframe: its patch aligned in the new image (sub-pixel), motion compensated, in the new
/// keyframe's sensor frame - the same measurement eq. (4) refined the pose with, so local BA
/// (Sec. III-B) sees what the odometry saw, not the detector's independent (jittered, biased)
/// position of the same landmark.
struct KeyframeObservation {
  int ref_index = -1;  ///< the previous keyframe's keypoint
  int cur_index = -1;  ///< the new keyframe's keypoint at that landmark (a descriptor inlier), or -1
  Eigen::Vector2d xy;  ///< measured position, new keyframe frame
  /// The information shape of `xy` (structure_information.h), new keyframe frame; identity = isotropic.
  Eigen::Matrix2d information = Eigen::Matrix2d::Identity();
};

struct OdometryStep {
  StampNs stamp = 0;           ///< the scan's reference time
  mrpt::math::TPose2D pose;    ///< radar pose in the first scan's frame
  mrpt::math::TPose2D motion;  ///< T_previous_current
  /// The constant-velocity prediction of `motion` the matches were searched around (zero without a
  /// velocity: the first scans, after a data gap).
  mrpt::math::TPose2D predicted_motion;
  /// The motion-prior search radius the matches were found in (the wide one when `widened`).
  SearchRadius search_radius;
  BodyVelocity velocity;  ///< body-frame velocity estimate after this scan
  TrackingStatus status = TrackingStatus::Initialised;
  int keypoints = 0, matches = 0, inliers = 0;
  bool clique_exact = true;
  bool widened = false;  ///< the adaptive radius found too few inliers; matched again with the wide one
  /// The second rigid motion of the matches was more likely than the maximum clique's
  /// (frontend/rigid_motion_choice.h): the largest rigid set was moving.
  bool second_motion = false;
  /// The estimate left the constant-velocity prediction by more than a road vehicle can
  /// (TrackingParams::max_acceleration_mps2): treated as a tracking loss (status Lost).
  bool implausible = false;
  /// The motion model's prior in eq. (4) (pose_refiner.h): its innovation chi^2 at the last
  /// refinement (-1: not weighed: no measured prediction error yet, or re-matched wide) and
  /// whether it passed its gate.
  double prior_chi2 = -1.0;
  bool prior_applied = false;
  bool new_keyframe = false;
  /// When new_keyframe: the new keyframe's keypoints in its sensor frame at the reference time
  /// (motion compensated) - the observations local mapping turns into map points - and, when it
  /// was tracked (not a re-initialisation), where the final estimate saw the previous keyframe's
  /// keypoints in the new keyframe (keyframe_observations).
  std::vector<Eigen::Vector2d> keyframe_points;
  /// Their information shapes (structure_information.h); empty when not estimated (isotropic).
  std::vector<Eigen::Matrix2d> keyframe_structure;
  std::vector<KeyframeObservation> keyframe_observations;
  StageTimes times;
};

class RadarOdometry {
 public:
  explicit RadarOdometry(const OdometryParams& params = {});
  ~RadarOdometry();
  RadarOdometry(const RadarOdometry&) = delete;
  RadarOdometry& operator=(const RadarOdometry&) = delete;

  /// Tracks one scan; scans must come in time order.
  OdometryStep process(const CObservationRadarScan& scan);

  /// Every processed scan's pose at its reference time.
  const Trajectory& trajectory() const;
  const OdometryParams& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radarslam
