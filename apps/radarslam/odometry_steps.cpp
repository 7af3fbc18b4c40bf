#include "odometry_steps.h"

#include "cli_common.h"

#include <cmath>
#include <string>

#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <radarslam/io/trajectory_files.h>

namespace radarslam::cli {
namespace {

double degrees(double rad) { return mrpt::RAD2DEG(mrpt::math::wrapToPi(rad)); }

/// The prediction's translation error at the sensor against the truth exceeds the search radius
/// there (SearchRadius::at(0): its fixed part).
bool outsideRadius(const StepRecord& s, const mrpt::math::TPose2D& truth) {
  const mrpt::math::TPose2D error = truth - s.predicted;
  return std::hypot(error.x, error.y) > s.search_radius.at(0.0);
}

}  // namespace

StepRecord recordOf(const OdometryStep& step) {
  StepRecord r;
  r.stamp = step.stamp;
  r.status = step.status;
  r.keypoints = step.keypoints, r.matches = step.matches, r.inliers = step.inliers;
  r.search_radius = step.search_radius;
  r.predicted = step.predicted_motion, r.estimated = step.motion;
  r.widened = step.widened, r.second_motion = step.second_motion, r.implausible = step.implausible;
  r.new_keyframe = step.new_keyframe;
  r.prior_chi2 = step.prior_chi2, r.prior_applied = step.prior_applied;
  r.ms = step.times.total();
  return r;
}

StepTruth trueMotions(const std::vector<StepRecord>& steps, const TruthAt& truth) {
  StepTruth motions(steps.size());
  std::optional<mrpt::math::TPose2D> previous;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const auto current = truth(steps[i].stamp);
    if (previous && current) motions[i] = *current - *previous;
    previous = current;
  }
  return motions;
}

std::string formatSteps(const std::vector<StepRecord>& steps, const std::optional<StepTruth>& truth) {
  std::string text =
      "stamp_s,status,keypoints,matches,inliers,radius_m,radius_per_m,pred_dx_m,pred_dy_m,pred_dyaw_deg,"
      "est_dx_m,est_dy_m,est_dyaw_deg,widened,second_motion,implausible,new_keyframe,track_ms,prior_chi2,"
      "prior_applied";
  if (truth) text += ",true_dx_m,true_dy_m,true_dyaw_deg,est_error_m,true_outside_radius";
  text += "\n";
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const StepRecord& s = steps[i];
    text += formatStampSeconds(s.stamp);
    text += ',';
    text += toString(s.status);
    text += formatText(",%d,%d,%d,%.4f,%.6f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%d,%d,%d,%.2f", s.keypoints,
                       s.matches, s.inliers, s.search_radius.at(0.0), s.search_radius.per_range,
                       s.predicted.x, s.predicted.y, degrees(s.predicted.phi), s.estimated.x, s.estimated.y,
                       degrees(s.estimated.phi), int{s.widened}, int{s.second_motion}, int{s.implausible},
                       int{s.new_keyframe}, s.ms);
    text += formatText(",%.2f,%d", s.prior_chi2, int{s.prior_applied});
    if (truth) {
      if (const auto& t = truth->at(i)) {
        const mrpt::math::TPose2D error = s.estimated - *t;
        text += formatText(",%.4f,%.4f,%.4f,%.4f,%d", t->x, t->y, degrees(t->phi),
                           std::hypot(error.x, error.y), int{outsideRadius(s, *t)});
      } else {
        text += ",,,,,";
      }
    }
    text += "\n";
  }
  return text;
}

StepTruthSummary summarizeTruth(const std::vector<StepRecord>& steps, const StepTruth& truth) {
  StepTruthSummary sum;
  for (std::size_t i = 0; i < steps.size() && i < truth.size(); ++i) {
    if (!truth[i]) continue;
    ++sum.compared;
    sum.outside_radius += outsideRadius(steps[i], *truth[i]);
    const TrackingStatus status = steps[i].status;
    if (status != TrackingStatus::Tracking && status != TrackingStatus::Recovered) continue;
    const double true_deg = degrees(truth[i]->phi), estimated_deg = degrees(steps[i].estimated.phi);
    if (std::abs(true_deg) < kStraightDeg) {
      ++sum.straight;
      sum.straight_heading_error_deg += degrees(mrpt::DEG2RAD(estimated_deg - true_deg));
    } else if (std::abs(true_deg) >= kTurningDeg) {
      ++sum.turning;
      sum.turning_true_deg += std::abs(true_deg);
      sum.turning_estimated_deg += true_deg < 0 ? -estimated_deg : estimated_deg;
    }
  }
  return sum;
}

}  // namespace radarslam::cli
