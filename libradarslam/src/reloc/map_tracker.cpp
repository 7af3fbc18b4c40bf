// Scan-to-submap tracking with acceptance tests; see reloc/map_tracker.h.
#include "radarslam/reloc/map_tracker.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, MapTrackerParams& p) {
  int min_inliers = static_cast<int>(p.min_inliers);
  yaml.get("min_fit_score", p.min_fit_score, Range::closed(0, 1));
  yaml.get("min_inliers", min_inliers, Range::closed(3, 1000000.0));
  yaml.get("max_rms_m", p.max_rms_m, Range::above(0, 100));
  yaml.get("max_jump_m", p.max_jump_m, Range::above(0, 1000));
  yaml.get("max_jump_deg", p.max_jump_deg, Range::above(0, 180));
  yaml.get("max_position_sigma_m", p.max_position_sigma_m, Range::above(0, 1000));
  p.min_inliers = static_cast<std::size_t>(min_inliers);
  loadParams(yaml.section("submap"), p.submap);
  loadParams(yaml.section("icp"), p.icp);
}

MapTracker::MapTracker(const KeyframeMap& map, const MapTrackerParams& params) : map_(map), params_(params) {}
MapTracker::~MapTracker() = default;

TrackResult MapTracker::track(std::span<const RadarPoint> cloud, const mrpt::math::TPose2D& predicted) {
  TrackResult out;
  if (!submap_ || std::hypot(predicted.x - submap_->centreX(), predicted.y - submap_->centreY()) >
                      params_.submap.rebuild_distance_m) {
    submap_ = LocalSubmap::build(map_, predicted.x, predicted.y, params_.submap);
    out.submap_rebuilt = true;
  }
  if (submap_->keyframes() == 0) {
    out.reason = "no map keyframe near the predicted pose";
    return out;
  }
  out.icp = submap_->registerScan(cloud, predicted, params_.icp);
  const IcpResult& r = out.icp;
  const double jump = std::hypot(r.pose.x - predicted.x, r.pose.y - predicted.y);
  const double jump_deg = std::abs(std::remainder(r.pose.phi - predicted.phi, 2 * M_PI)) * 180.0 / M_PI;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(r.covariance.topLeftCorner<2, 2>());
  const double sigma_xy = std::sqrt(std::max(0.0, es.eigenvalues()(1)));
  char buf[160];
  if (r.inliers < params_.min_inliers) {
    std::snprintf(buf, sizeof buf, "%zu inliers < %zu", r.inliers, params_.min_inliers);
  } else if (r.fit_score < params_.min_fit_score) {
    std::snprintf(buf, sizeof buf, "fit %.2f < %.2f", r.fit_score, params_.min_fit_score);
  } else if (r.rms_m > params_.max_rms_m) {
    std::snprintf(buf, sizeof buf, "rms %.2f m > %.2f m", r.rms_m, params_.max_rms_m);
  } else if (jump > params_.max_jump_m || jump_deg > params_.max_jump_deg) {
    std::snprintf(buf, sizeof buf, "jump %.2f m / %.1f deg from the prediction", jump, jump_deg);
  } else if (!(sigma_xy <= params_.max_position_sigma_m)) {
    std::snprintf(buf, sizeof buf, "position sigma %.2f m > %.2f m", sigma_xy, params_.max_position_sigma_m);
    out.degenerate = true;
  } else {
    out.accepted = true;
    return out;
  }
  out.reason = buf;
  return out;
}

}  // namespace radarslam
