#pragma once
// `radarslam odometry --steps FILE`: one CSV row per scan with what the tracker saw and decided -
// status, keypoints, matches, inliers, the motion-prior search radius, the predicted and the
// estimated motion, the stage times - and, when the dataset has ground truth, the true motion and
// whether it lay outside the search radius (the prediction's error at the sensor larger than the
// radius: those scans could not be matched right; docs/evaluation.md, "The wall in fog").
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include <radarslam/frontend/odometry.h>

namespace radarslam::cli {

/// What one scan's row keeps of its OdometryStep.
struct StepRecord {
  StampNs stamp = 0;
  TrackingStatus status = TrackingStatus::Initialised;
  int keypoints = 0, matches = 0, inliers = 0;
  SearchRadius search_radius;
  mrpt::math::TPose2D predicted, estimated;  ///< T_previous_current
  bool widened = false, second_motion = false, implausible = false, new_keyframe = false;
  double prior_chi2 = -1.0;  ///< OdometryStep::prior_chi2
  bool prior_applied = false;
  double ms = 0.0;  ///< the tracker's stage times summed
};

StepRecord recordOf(const OdometryStep& step);

/// The ground truth pose at a stamp (nullopt outside its time span).
using TruthAt = std::function<std::optional<mrpt::math::TPose2D>(StampNs)>;

/// Each step's true motion T_previous_current (nullopt for the first step and wherever the ground
/// truth does not cover both scans).
using StepTruth = std::vector<std::optional<mrpt::math::TPose2D>>;
StepTruth trueMotions(const std::vector<StepRecord>& steps, const TruthAt& truth);

/// The CSV text (header line first). With `truth` (one entry per step) the true motion columns are
/// added, filled where the truth is known and left empty elsewhere.
std::string formatSteps(const std::vector<StepRecord>& steps, const std::optional<StepTruth>& truth);

/// A scan whose true heading change is below this goes straight; at or above kTurningDeg it turns.
constexpr double kStraightDeg = 0.05, kTurningDeg = 0.5;

/// Summary of the truth columns: scans whose true motion lay outside the search radius, and the
/// heading of the tracked scans (tracking or recovered; a lost scan's motion is the prediction):
/// the mean heading error on straight scans (a bias that turns a straight road;
/// docs/odometry.md, "Heading bias on straight roads") and the estimated share of the turns.
struct StepTruthSummary {
  std::size_t compared = 0, outside_radius = 0;
  std::size_t straight = 0, turning = 0;
  double straight_heading_error_deg = 0.0;                     ///< summed over the straight scans
  double turning_estimated_deg = 0.0, turning_true_deg = 0.0;  ///< |heading change| summed over turning scans
};
StepTruthSummary summarizeTruth(const std::vector<StepRecord>& steps, const StepTruth& truth);

}  // namespace radarslam::cli
