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

/// Summary of the truth columns: scans whose true motion lay outside the search radius.
struct StepTruthSummary {
  std::size_t compared = 0, outside_radius = 0;
};
StepTruthSummary summarizeTruth(const std::vector<StepRecord>& steps, const StepTruth& truth);

}  // namespace radarslam::cli
