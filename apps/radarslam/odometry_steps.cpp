#include "odometry_steps.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <radarslam/io/trajectory_files.h>

namespace radarslam::cli {
namespace {

double degrees(double rad) { return std::remainder(rad, 2.0 * M_PI) * 180.0 / M_PI; }

/// T_previous_current from the ground truth at both stamps.
std::optional<mrpt::math::TPose2D> trueMotion(const TruthAt& truth, StampNs prev, StampNs cur) {
  if (!truth) return std::nullopt;
  const auto a = truth(prev), b = truth(cur);
  if (!a || !b) return std::nullopt;
  return *b - *a;
}

/// The prediction's translation error at the sensor against the truth exceeds the search radius
/// there (SearchRadius::at(0): its fixed part).
bool outsideRadius(const StepRecord& s, const mrpt::math::TPose2D& truth) {
  const mrpt::math::TPose2D error = truth - s.predicted;
  return std::hypot(error.x, error.y) > s.search_radius.at(0.0);
}

std::string format(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
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
  r.ms = step.times.total();
  return r;
}

std::string formatSteps(const std::vector<StepRecord>& steps, const TruthAt& truth) {
  std::string text =
      "stamp_s,status,keypoints,matches,inliers,radius_m,radius_per_m,pred_dx_m,pred_dy_m,pred_dyaw_deg,"
      "est_dx_m,est_dy_m,est_dyaw_deg,widened,second_motion,implausible,new_keyframe,track_ms";
  if (truth) text += ",true_dx_m,true_dy_m,true_dyaw_deg,est_error_m,true_outside_radius";
  text += "\n";
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const StepRecord& s = steps[i];
    text += formatStampSeconds(s.stamp) + "," + toString(s.status);
    text +=
        format(",%d,%d,%d,%.4f,%.6f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%d,%d,%d,%.2f", s.keypoints, s.matches,
               s.inliers, s.search_radius.at(0.0), s.search_radius.per_range, s.predicted.x, s.predicted.y,
               degrees(s.predicted.phi), s.estimated.x, s.estimated.y, degrees(s.estimated.phi),
               int{s.widened}, int{s.second_motion}, int{s.implausible}, int{s.new_keyframe}, s.ms);
    if (truth) {
      const auto t = i > 0 ? trueMotion(truth, steps[i - 1].stamp, s.stamp) : std::nullopt;
      if (t) {
        const mrpt::math::TPose2D error = s.estimated - *t;
        text += format(",%.4f,%.4f,%.4f,%.4f,%d", t->x, t->y, degrees(t->phi), std::hypot(error.x, error.y),
                       int{outsideRadius(s, *t)});
      } else {
        text += ",,,,,";
      }
    }
    text += "\n";
  }
  return text;
}

StepTruthSummary summarizeTruth(const std::vector<StepRecord>& steps, const TruthAt& truth) {
  StepTruthSummary sum;
  for (std::size_t i = 1; i < steps.size(); ++i) {
    const auto t = trueMotion(truth, steps[i - 1].stamp, steps[i].stamp);
    if (!t) continue;
    ++sum.compared;
    sum.outside_radius += outsideRadius(steps[i], *t);
  }
  return sum;
}

}  // namespace radarslam::cli
