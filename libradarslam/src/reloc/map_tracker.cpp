// Scan-to-submap tracking with acceptance tests; see reloc/map_tracker.h.
#include "radarslam/reloc/map_tracker.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/map/keyframe_search.h"
#include "radarslam/reloc/integrity.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, MapTrackerParams& p) {
  int min_inliers = static_cast<int>(p.min_inliers);
  yaml.get("min_fit_score", p.min_fit_score, Range::closed(0, 1));
  yaml.get("min_inliers", min_inliers, Range::closed(3, 1000000.0));
  yaml.get("max_rms_m", p.max_rms_m, Range::above(0, 100));
  yaml.get("max_jump_m", p.max_jump_m, Range::above(0, 1000));
  yaml.get("max_jump_deg", p.max_jump_deg, Range::above(0, 180));
  yaml.get("max_position_sigma_m", p.max_position_sigma_m, Range::above(0, 1000));
  yaml.get("ambiguity_fit_ratio", p.ambiguity_fit_ratio, Range::closed(0, 1));
  yaml.get("reacquisition_starts", p.reacquisition_starts, Range::closed(0, 10));
  yaml.get("anchor_path_m", p.anchor_path_m, Range::closed(0, 10000));
  p.min_inliers = static_cast<std::size_t>(min_inliers);
  loadParams(yaml.section("submap"), p.submap);
  loadParams(yaml.section("icp"), p.icp);
}

namespace {
// The registration's model errors for this kind of map (IcpParams: raw sweeps or SLAM clouds).
MapTrackerParams forMap(MapTrackerParams p, const KeyframeMap& map) {
  if (map.meta.clouds_motion_compensated) {
    p.icp.heading_sigma_floor_deg = p.icp.slam_map_heading_sigma_floor_deg;
    p.icp.position_sigma_floor_m = p.icp.slam_map_position_sigma_floor_m;
  }
  return p;
}
}  // namespace

bool differentAlignments(const IcpResult& a, const IcpResult& b, const IcpParams& icp) {
  return std::hypot(a.pose.x - b.pose.x, a.pose.y - b.pose.y) > icp.inlier_distance_m ||
         std::abs(std::remainder(a.pose.phi - b.pose.phi, 2 * M_PI)) * 180.0 / M_PI > 1.0;
}

MapTracker::MapTracker(const KeyframeMap& map, const MapTrackerParams& params)
    : map_(map), params_(forMap(params, map)), connectivity_(map), agreement_(map.keyframes.size()) {}
MapTracker::~MapTracker() = default;

void MapTracker::rebuild(const mrpt::math::TPose2D& predicted, long anchor) {
  built_for_anchor_ = anchor;
  other_.reset();
  if (anchor < 0 || params_.submap.max_path_m <= 0) {
    submap_ = LocalSubmap::build(map_, predicted.x, predicted.y, params_.submap);
    return;
  }
  std::vector<char> copy = connectivity_.within(static_cast<std::size_t>(anchor), params_.submap.max_path_m);
  submap_ = LocalSubmap::build(map_, predicted.x, predicted.y, params_.submap, &copy);
  for (char& c : copy) c = !c;
  LocalSubmap other = LocalSubmap::build(map_, predicted.x, predicted.y, params_.submap, &copy);
  if (other.keyframes() > 0) other_ = std::move(other);
}

Eigen::Matrix3d MapTracker::reacquire(const std::vector<Eigen::Vector2d>& thinned,
                                      const mrpt::math::TPose2D& predicted,
                                      const Eigen::Matrix3d& predicted_cov, TrackResult& out) const {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(predicted_cov.topLeftCorner<2, 2>());
  // Wide = 3 sigma beyond what tells two alignments apart along the largest xy axis (the inlier
  // gate, differentAlignments), or in heading beyond the ICP's capture range (its first gate at the
  // submap's radius; an ordinary prediction's heading 3 sigma, ~1.2 deg, is already above 1 deg,
  // and the ICP's own iterations search its capture range).
  const double reach = 3 * std::sqrt(std::max(0.0, es.eigenvalues()(1)));
  const double reach_rad = 3 * std::sqrt(std::max(0.0, predicted_cov(2, 2)));
  const double capture_rad = params_.headingCaptureRad();
  const bool wide_xy = reach > params_.icp.inlier_distance_m;
  const bool wide_phi = reach_rad > capture_rad;
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  if (params_.reacquisition_starts <= 0 || (!wide_xy && !wide_phi)) return spread;
  out.reacquisition = true;
  // Starts k = 1..per_side steps of `unit` (a pose offset per unit of reach) on each side, spaced
  // by the capture range, out to the reach.
  std::vector<mrpt::math::TPose2D> from;
  auto addStarts = [&](double reach_along, double capture, const Eigen::Vector3d& unit) {
    const double step = std::min(reach_along, capture);
    const int per_side =
        std::min(params_.reacquisition_starts, static_cast<int>(std::ceil(reach_along / step - 1e-9)));
    for (int k = 1; k <= per_side; ++k)
      for (const double sign : {-1.0, 1.0}) {
        const Eigen::Vector3d d = sign * k * step * unit;
        from.push_back({predicted.x + d.x(), predicted.y + d.y(), predicted.phi + d.z()});
      }
  };
  if (wide_xy) {
    const Eigen::Vector2d axis = es.eigenvectors().col(1).normalized();
    addStarts(reach, params_.icp.max_correspondence_m, Eigen::Vector3d(axis.x(), axis.y(), 0));
  }
  if (wide_phi) addStarts(reach_rad, capture_rad, Eigen::Vector3d::UnitZ());
  std::vector<IcpResult> found{out.icp};
  for (const auto& start : from) {
    IcpResult r = submap_->registerThinned(thinned, start, params_.icp);
    if (r.inliers >= params_.min_inliers) found.push_back(std::move(r));
  }
  // The registration's likelihood in its own (calibrated) units: 2 cost / (covariance_scale sigma^2),
  // whose differences are d^T Sigma^-1 d near a minimum (IcpResult::cost); sigma^2 of the
  // registration from the prediction, so that every alignment is measured in one unit.
  const double unit = params_.icp.covariance_scale * std::max(found.front().sigma2, 1e-12);
  const Eigen::Matrix3d prior_information = predicted_cov.inverse();
  auto posterior = [&](const IcpResult& r) {
    const Eigen::Vector3d d(r.pose.x - predicted.x, r.pose.y - predicted.y,
                            std::remainder(r.pose.phi - predicted.phi, 2 * M_PI));
    return 2 * r.cost / unit + d.dot(prior_information * d);
  };
  // Kept: the most probable alignment given the prediction (the first on a tie: the registration
  // from the prediction itself).
  const auto best = std::min_element(found.begin(), found.end(), [&](const IcpResult& a, const IcpResult& b) {
    return posterior(a) < posterior(b);
  });
  const IcpResult kept = *best;
  // A rival: another alignment the scan itself does not tell from the kept one, its likelihood
  // within the chi^2(3) bound (rival_chi2) of the kept's; the prediction, wide here, is not asked.
  int rivals = 0;
  for (const IcpResult& r : found) {
    if (!differentAlignments(r, kept, params_.icp) || 2 * (r.cost - kept.cost) / unit > params_.rival_chi2)
      continue;
    const Eigen::Vector3d d(r.pose.x - kept.pose.x, r.pose.y - kept.pose.y,
                            std::remainder(r.pose.phi - kept.pose.phi, 2 * M_PI));
    spread += d * d.transpose();
    ++rivals;
  }
  out.icp = kept;
  out.reacquisition_ambiguous = rivals > 0;
  return rivals > 0 ? Eigen::Matrix3d(spread / static_cast<double>(rivals + 1))  // second moment, kept at 0
                    : Eigen::Matrix3d::Zero();
}

const MapTracker::KeyframeAgreement& MapTracker::keyframeAgreement(std::size_t k) {
  KeyframeAgreement& a = agreement_[k];
  if (a.evaluated) return a;
  a.evaluated = true;
  std::vector<char> others = connectivity_.within(k, params_.anchor_path_m);
  others[k] = 0;
  const Keyframe& kf = map_.keyframes[k];
  const LocalSubmap neighbours = LocalSubmap::build(map_, kf.pose.x, kf.pose.y, params_.submap, &others);
  if (neighbours.keyframes() == 0) return a;
  const IcpResult r = neighbours.registerThinned(LocalSubmap::thinScan(toRadarPoints(kf.points), params_.icp),
                                                 kf.pose, params_.icp);
  if (r.inliers < params_.min_inliers) return a;
  a.offset = poseDifference(kf.pose, r.pose);
  a.chi2 = mahalanobis2(a.offset, r.covariance);
  return a;
}

void MapTracker::checkAnchor(const std::vector<Eigen::Vector2d>& thinned, TrackResult& out) {
  if (params_.anchor_path_m <= 0 || out.anchor < 0 || out.icp.inliers < params_.min_inliers) return;
  const KeyframeAgreement& kf = keyframeAgreement(static_cast<std::size_t>(out.anchor));
  out.anchor_keyframe_chi2 = kf.chi2;
  if (kf.chi2 > params_.rival_chi2) {
    out.map_inconsistent = true;
    out.map_disagreement += kf.offset * kf.offset.transpose();
  }
  // The scan's test: against the anchor keyframe's own cloud (nothing else to disagree with when
  // the submap holds only the anchor).
  if (submap_->keyframes() <= 1) return;
  if (anchor_submap_for_ != out.anchor) {
    std::vector<char> only(map_.keyframes.size(), 0);
    only[static_cast<std::size_t>(out.anchor)] = 1;
    const auto& pose = map_.keyframes[static_cast<std::size_t>(out.anchor)].pose;
    anchor_submap_ = LocalSubmap::build(map_, pose.x, pose.y, params_.submap, &only);
    anchor_submap_for_ = out.anchor;
  }
  out.anchor_alignment = anchor_submap_->registerThinned(thinned, out.icp.pose, params_.icp);
  const IcpResult& a = out.anchor_alignment;
  if (a.inliers < params_.min_inliers) return;  // too little of the scan there to tell
  const Eigen::Vector3d d = poseDifference(out.icp.pose, a.pose);
  out.anchor_chi2 = mahalanobis2(d, a.covariance);
  if (out.anchor_chi2 > params_.rival_chi2) {
    out.map_inconsistent = out.anchor_alignment_differs = true;
    out.map_disagreement += d * d.transpose();
  }
}

TrackResult MapTracker::track(std::span<const RadarPoint> cloud, const mrpt::math::TPose2D& predicted,
                              long anchor, const Eigen::Matrix3d* predicted_cov) {
  TrackResult out;
  // Rebuilt when the prediction moved far enough, or when asked to track another copy (an anchor
  // the current submap does not hold, e.g. after a new global fix).
  auto sameCopy = [&] {
    if (anchor == built_for_anchor_) return true;
    if (anchor < 0 || built_for_anchor_ < 0) return false;
    const auto& ids = submap_->keyframeIndices();
    return std::binary_search(ids.begin(), ids.end(), static_cast<std::size_t>(anchor));
  };
  if (!submap_ ||
      std::hypot(predicted.x - submap_->centreX(), predicted.y - submap_->centreY()) >
          params_.submap.rebuild_distance_m ||
      !sameCopy()) {
    rebuild(predicted, anchor);
    out.submap_rebuilt = true;
  }
  if (submap_->keyframes() == 0) {
    out.reason = "no map keyframe near the predicted pose";
    return out;
  }
  const std::vector<Eigen::Vector2d> thinned = LocalSubmap::thinScan(cloud, params_.icp);
  out.icp = submap_->registerThinned(thinned, predicted, params_.icp);
  const Eigen::Matrix3d spread =
      predicted_cov ? reacquire(thinned, predicted, *predicted_cov, out) : Eigen::Matrix3d::Zero();
  if (checksProfile()) submap_->fitProfile(thinned, params_.icp, out.icp);  // of the kept alignment
  out.icp.covariance += spread;
  const IcpResult& r = out.icp;
  out.anchor = nearestKeyframe(map_, submap_->keyframeIndices(), r.pose.x, r.pose.y);
  checkAnchor(thinned, out);
  if (other_) {  // a second copy of this place: does it explain the scan elsewhere as well?
    out.alternative = other_->registerThinned(thinned, predicted, params_.icp);
    const IcpResult& a = out.alternative;
    out.ambiguous = a.inliers >= params_.min_inliers &&
                    a.fit_score >= params_.ambiguity_fit_ratio * r.fit_score &&
                    differentAlignments(a, r, params_.icp);
  }
  const double jump = std::hypot(r.pose.x - predicted.x, r.pose.y - predicted.y);
  const double jump_deg = std::abs(std::remainder(r.pose.phi - predicted.phi, 2 * M_PI)) * 180.0 / M_PI;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(r.covariance.topLeftCorner<2, 2>());
  const double sigma_xy = std::sqrt(std::max(0.0, es.eigenvalues()(1)));
  // Check (g): the solution shifted by profile_shift_m along the weakest direction is not told apart
  // from it by the scan (the likelihood ratio within check (h)'s rival bound): the cost is flat
  // there, the position along it known only to about the shift, whichever check makes the scan
  // degenerate.
  const bool flat = checksProfile() && r.profile_chi2 <= params_.rival_chi2;
  auto inflateAlongTheFlatDirection = [&] {
    const double shift2 = params_.icp.profile_shift_m * params_.icp.profile_shift_m;
    out.icp.covariance.topLeftCorner<2, 2>() += shift2 * r.weak_direction * r.weak_direction.transpose();
  };
  char buf[200];
  if (r.inliers < params_.min_inliers) {
    std::snprintf(buf, sizeof buf, "%zu inliers < %zu", r.inliers, params_.min_inliers);
  } else if (r.fit_score < params_.min_fit_score) {
    std::snprintf(buf, sizeof buf, "fit %.2f < %.2f", r.fit_score, params_.min_fit_score);
  } else if (r.rms_m > params_.max_rms_m) {
    std::snprintf(buf, sizeof buf, "rms %.2f m > %.2f m", r.rms_m, params_.max_rms_m);
  } else if (jump > params_.max_jump_m || jump_deg > params_.max_jump_deg) {
    std::snprintf(buf, sizeof buf, "jump %.2f m / %.1f deg from the prediction", jump, jump_deg);
  } else if (out.reacquisition_ambiguous) {
    std::snprintf(buf, sizeof buf,
                  "re-acquisition: another alignment within the prediction's 3 sigma fits as well%s",
                  flat ? "; flat along its weakest direction" : "");
    out.degenerate = true;
    if (flat) inflateAlongTheFlatDirection();
  } else if (!(sigma_xy <= params_.max_position_sigma_m)) {
    std::snprintf(buf, sizeof buf, "position sigma %.2f m > %.2f m%s", sigma_xy, params_.max_position_sigma_m,
                  flat ? "; flat along its weakest direction" : "");
    out.degenerate = true;
    if (flat) inflateAlongTheFlatDirection();
  } else if (flat) {
    std::snprintf(buf, sizeof buf,
                  "flat along its weakest direction: likelihood ratio %.1f <= %.1f shifted %.1f m (fit %.2f, "
                  "%.2f at the solution)",
                  r.profile_chi2, params_.rival_chi2, params_.icp.profile_shift_m, r.profile_fit,
                  r.fit_score);
    inflateAlongTheFlatDirection();
    out.degenerate = true;
  } else {
    out.accepted = true;
    return out;
  }
  out.reason = buf;
  return out;
}

}  // namespace radarslam
