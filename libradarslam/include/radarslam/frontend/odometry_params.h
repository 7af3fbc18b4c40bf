#pragma once
// Every parameter of the radar odometry (front end), with defaults; config/<sensor>.yaml
// overrides them under the `cartesian:` and `odometry:` sections.
#include <string>

#include "radarslam/frontend/keyframe_policy.h"
#include "radarslam/frontend/keypoints.h"
#include "radarslam/frontend/patch_alignment.h"
#include "radarslam/frontend/pose_refiner.h"
#include "radarslam/frontend/radius_matcher.h"
#include "radarslam/radar/cartesian.h"
#include "radarslam/radar/doppler_compensation.h"

namespace radarslam {

class YamlParams;

struct OutlierParams {
  bool max_clique = true;                ///< eq. (3) graph + maximum clique; false = all matches (ablation)
  double delta_c_m = 0.75;               ///< eq. (3) threshold (authors: 3 px at 0.25 m/px); valid (0, 100]
  std::string consistency = "distance";  ///< distance (rigid invariant) | displacement (eq. (3) as printed)
  int max_matches = 500;                 ///< best-descriptor matches fed to the graph; valid [3, 5000]
  long max_clique_steps = 20000;         ///< branch-and-bound budget; valid [1, 1e8]
  double inlier_gate_m =
      1.0;  ///< after the SVD pose, matches within this are inliers for eq. (4); valid (0, 100]
  /// Weigh the maximum clique against the second rigid motion (the maximum clique of the other
  /// matches) by their likelihoods under the constant-velocity prediction (frontend/rigid_motion_choice.h).
  bool second_motion = true;
};

struct TrackingParams {
  int min_inliers = 10;  ///< fewer -> tracking lost for this scan; valid [3, 100000]
  double min_range_m =
      3.0;  ///< keypoints closer than this are ignored (sensor/vehicle clutter); valid [0, 1000]
  double max_speed_mps = 40.0;  ///< estimates implying more are rejected as failures; valid (0, 1000]
  // A road vehicle's largest acceleration (1 g: tyre friction) bounds how far an estimate (and a
  // wide re-match) may move the translation from the constant-velocity prediction; beyond it the
  // scan is lost (constant-velocity prediction).
  double max_acceleration_mps2 = 10.0;  ///< physical bound on the velocity change per scan; valid (0, 1000]
  int keep_keyframe_when_lost =
      2;  ///< consecutive lost scans with too few keypoints that keep the keyframe; valid [0, 1000]
  bool motion_compensation = true;
  bool acceleration_aware = true;  ///< per-scan velocity from neighbouring pairs, not the pair's mean
  int compensation_passes = 2;  ///< re-compensate with the refined velocity and refine again; valid [0, 10]
  double max_prediction_gap_s =
      1.0;  ///< longer intervals (data gaps) re-initialise, no constant velocity; valid (0, 3600]
};

struct OdometryParams {
  CartesianParams cartesian;
  KeypointParams keypoints;
  MatchParams matching;
  OutlierParams outliers;
  PatchAlignParams patch_alignment;
  RefineParams refine;
  KeyframeParams keyframes;
  TrackingParams tracking;
  /// Doppler range offset removal (radar/doppler_compensation.h) with the tracked ego velocity.
  DopplerParams doppler;
};

/// Overrides from `cartesian:` and `odometry:` {keypoints, matching, outliers, refine, keyframes,
/// tracking, doppler} of `yaml`. Throws InputError for bad values.
void loadParams(const YamlParams& yaml, OdometryParams& params);

}  // namespace radarslam
