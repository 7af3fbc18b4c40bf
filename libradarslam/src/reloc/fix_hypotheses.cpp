// Contested global fixes resolved over consecutive scans; see reloc/fix_hypotheses.h.
#include "radarslam/reloc/fix_hypotheses.h"

#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <cmath>

#include "radarslam/core/se2_covariance.h"
#include "radarslam/map/keyframe_search.h"
#include "radarslam/reloc/integrity.h"

namespace radarslam {

FixHypotheses::FixHypotheses(MapTracker& tracker, const KeyframeMap& map, double chi2_threshold)
    : tracker_(tracker), map_(map), chi2_threshold_(chi2_threshold) {}

bool FixHypotheses::usable(const TrackResult& r, const Gate& gate) const {
  return (r.accepted || r.degenerate) && (!gate || gate(r));
}

bool FixHypotheses::captured(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) const {
  const MapTrackerParams& p = tracker_.params();
  return std::hypot(a.x - b.x, a.y - b.y) <= p.icp.max_correspondence_m &&
         std::abs(std::remainder(a.phi - b.phi, 2 * M_PI)) <= p.headingCaptureRad();
}

void FixHypotheses::support(const std::vector<ContestedPlace>& places) {
  for (FixHypothesis& h : live_) {
    const bool pointed = std::any_of(places.begin(), places.end(), [&](const ContestedPlace& place) {
      return std::any_of(place.poses.begin(), place.poses.end(),
                         [&](const mrpt::math::TPose2D& pose) { return captured(h.last.icp.pose, pose); });
    });
    h.support += pointed;
  }
}

void FixHypotheses::seed(std::span<const RadarPoint> cloud, const std::vector<ContestedPlace>& places,
                         const Gate& gate) {
  std::vector<mrpt::math::TPose2D> starts;
  for (const ContestedPlace& place : places)
    for (const auto& pose : place.poses)
      if (std::none_of(starts.begin(), starts.end(), [&](const auto& s) { return captured(s, pose); }))
        starts.push_back(pose);
  live_.clear();
  registrations_ = 0;
  for (const auto& start : starts) {
    TrackResult r = tracker_.track(cloud, start, nearestKeyframe(map_, start.x, start.y));
    ++registrations_;
    if (usable(r, gate)) live_.push_back({std::move(r), 1, 1, 0.0});
  }
  prune();
}

void FixHypotheses::advance(std::span<const RadarPoint> cloud, const mrpt::math::TPose2D& motion,
                            const Eigen::Matrix3d& motion_cov, const Gate& gate) {
  registrations_ = 0;
  std::vector<FixHypothesis> next;
  for (FixHypothesis& h : live_) {
    const mrpt::math::TPose2D& from = h.last.icp.pose;
    const mrpt::math::TPose2D predicted =
        (mrpt::poses::CPose2D(from) + mrpt::poses::CPose2D(motion)).asTPose();
    const Eigen::Matrix3d predicted_cov = composeCovariance(from, h.last.icp.covariance, motion, motion_cov);
    TrackResult r = tracker_.track(cloud, predicted, h.last.anchor);
    ++registrations_;
    if (!usable(r, gate)) continue;
    // The map-relative motion must agree with the odometry's (the tracker's check (a)).
    if (mahalanobis2(poseDifference(predicted, r.icp.pose), predicted_cov + r.icp.covariance) >
        chi2_threshold_)
      continue;
    ++h.scans;
    h.last = std::move(r);
    next.push_back(std::move(h));
  }
  live_ = std::move(next);
  prune();
}

void FixHypotheses::prune() {
  if (live_.empty()) return;
  // This scan's evidence: each robust cost over the best one's, a likelihood ratio in the best
  // registration's calibrated unit (as MapTracker's check (h) compares two alignments).
  const MapTrackerParams& p = tracker_.params();
  const IcpResult& best =
      std::min_element(live_.begin(), live_.end(), [](const FixHypothesis& a, const FixHypothesis& b) {
        return a.last.icp.cost < b.last.icp.cost;
      })->last.icp;
  const double unit = p.icp.covariance_scale * best.sigma2;
  for (FixHypothesis& h : live_) h.chi2 += unit > 0 ? 2 * (h.last.icp.cost - best.cost) / unit : 0.0;
  // Most likely first (the older one wins a tie): a duplicate alignment keeps the likelier.
  std::stable_sort(live_.begin(), live_.end(),
                   [](const FixHypothesis& a, const FixHypothesis& b) { return a.chi2 < b.chi2; });
  std::vector<FixHypothesis> kept;
  for (FixHypothesis& h : live_) {
    if (h.chi2 > p.rival_chi2) break;
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const FixHypothesis& k) {
      return !differentAlignments(h.last.icp, k.last.icp, p.icp);
    });
    if (!duplicate) kept.push_back(std::move(h));
  }
  live_ = std::move(kept);
}

const FixHypothesis* FixHypotheses::unique(int min_scans) const {
  return live_.size() == 1 && live_.front().scans >= min_scans && live_.front().support >= min_scans
             ? &live_.front()
             : nullptr;
}

}  // namespace radarslam
