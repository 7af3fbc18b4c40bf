#pragma once
// Contested global fixes, resolved over consecutive scans (issue 14: first fix from any start).
// The verifier compares the scan with one keyframe's cloud, and in a car park or a street of
// look-alike blocks another alignment of that cloud scores almost as well (LoopVerification::rivals,
// 11-84 m and up to 180 deg away on the train sequences); with the whole local submap a single car
// park scan still fits elsewhere 0.83-0.99 as well (docs/localization.md). What tells the places
// apart is the drive: the vehicle moves on, and a wrong alignment, carried with the odometry, runs
// into map that does not match.
//
// Each pose the verifier refused only as ambiguous (the alignment and its rivals) seeds a
// hypothesis. Each scan every hypothesis is moved by the odometry motion and the scan registered
// against the map around it (MapTracker: the tracking registration and its tests). A hypothesis is
// dropped when
//   - its registration fails (neither accepted nor only degenerate: a weak direction),
//   - the registered motion disagrees with the odometry's (chi^2 of the innovation, as the
//     tracker's check (a)), or the caller's gate (the dead-reckoned prior) rules it out,
//   - another hypothesis is the same alignment (differentAlignments false: the better one stays),
//   - the evidence against it adds up: the sum over its scans of the likelihood ratio of its
//     registration to the best hypothesis's (2 delta robust cost in the best's calibrated unit,
//     IcpResult::cost) exceeds tracker.rival_chi2, the bound of check (h) applied to the scans
//     together (until 2026-12-06 the product of fit ratios against tracker.ambiguity_fit_ratio: in a
//     car park a wrong alignment fits 0.83-0.99 as well as the right one scan by scan).
// A single surviving hypothesis registered in confirm_fixes consecutive scans, which the global
// search of confirm_fixes scans pointed at (the seed counts; later scans' contested places within the
// capture range of it), is a fix: what "confirm_fixes agreeing fixes" asks of a verified place, with
// every rival ruled out by the map. Surviving its rivals does not make a place right when the right
// one was never seeded: in the train snowy avenue (start at scan 99) the right keyframe is not
// retrieved, and a look-alike 248 m away, pointed at by the search in both scans, survived its
// rivals (docs/localization.md, "Contested first fixes"; LocalizerParams::resolve_contested_fixes
// is off by default).
// The set is seeded once, from the first scan with contested places; while it lives, the global
// search goes on in parallel (a verified fix ends it).
#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>
#include <functional>
#include <span>
#include <vector>

#include "radarslam/map/keyframe_map.h"
#include "radarslam/radar/peak_cloud.h"
#include "radarslam/reloc/global_localizer.h"
#include "radarslam/reloc/map_tracker.h"

namespace radarslam {

struct FixHypothesis {
  TrackResult last;  ///< the latest registration (pose, covariance, anchor, tests' outcome)
  int scans = 0;     ///< consecutive scans registered
  int support = 0;   ///< scans whose global search pointed at it (contested places), the seed included
  /// Sum over its scans of 2 (its robust cost - the best hypothesis's) / (icp.covariance_scale
  /// sigma^2 of the best): the likelihood ratio against the best, >= 0.
  double chi2 = 0;
};

class FixHypotheses {
 public:
  /// `chi2_threshold`: the chi^2(3) bound of the odometry innovation test.
  /// `gate(r)`: false rules a registration out (the dead-reckoned prior); empty = none.
  using Gate = std::function<bool(const TrackResult&)>;
  /// Keeps references to `tracker` and `map` (must outlive this).
  FixHypotheses(MapTracker& tracker, const KeyframeMap& map, double chi2_threshold);

  /// Replaces the hypotheses by `places`: registers `cloud` (sensor frame, motion compensated) from
  /// each of their poses (starts within the ICP's capture range of one already registered,
  /// icp.max_correspondence_m and that distance at the submap radius in heading, are registered
  /// once), keeps the usable ones and prunes.
  void seed(std::span<const RadarPoint> cloud, const std::vector<ContestedPlace>& places,
            const Gate& gate = {});

  /// Moves every hypothesis by `motion` (T_prev_cur of the odometry, covariance `motion_cov`),
  /// registers `cloud` from there and prunes (see the file comment).
  void advance(std::span<const RadarPoint> cloud, const mrpt::math::TPose2D& motion,
               const Eigen::Matrix3d& motion_cov, const Gate& gate = {});

  /// Counts this scan's global search for every hypothesis within the capture range of one of the
  /// places' poses (after advance(), on the same scan).
  void support(const std::vector<ContestedPlace>& places);

  /// The only hypothesis left, when it has been registered in at least `min_scans` consecutive
  /// scans and supported by as many global searches; nullptr otherwise.
  const FixHypothesis* unique(int min_scans) const;

  void clear() { live_.clear(); }
  bool empty() const { return live_.empty(); }
  std::size_t size() const { return live_.size(); }
  const std::vector<FixHypothesis>& hypotheses() const { return live_; }
  /// Registrations of the last seed() or advance().
  std::size_t registrations() const { return registrations_; }

 private:
  bool usable(const TrackResult& r, const Gate& gate) const;
  /// Within the ICP's capture range (icp.max_correspondence_m; in heading, that at the submap radius).
  bool captured(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) const;
  void prune();

  MapTracker& tracker_;
  const KeyframeMap& map_;
  double chi2_threshold_;
  std::vector<FixHypothesis> live_;
  std::size_t registrations_ = 0;
};

}  // namespace radarslam
