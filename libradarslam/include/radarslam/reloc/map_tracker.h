#pragma once
// Tracking against a stored map once localised: the scan's peak cloud is registered (robust ICP,
// reloc/submap_icp.h) against the local submap around the predicted pose (the previous map pose
// composed with the odometry motion T_prev_cur). The result is trusted only if it passes every
// test below; otherwise the caller must treat the scan as not localised.
#include <mrpt/math/TPose2D.h>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "radarslam/reloc/map_connectivity.h"
#include "radarslam/reloc/submap_icp.h"

namespace radarslam {

class YamlParams;

struct MapTrackerParams {
  SubmapParams submap;
  IcpParams icp;
  double min_fit_score = 0.35;   ///< inliers / scan points; valid [0, 1]
  std::size_t min_inliers = 60;  ///< valid [3, 1000000]
  double max_rms_m = 0.6;        ///< valid (0, 100]
  double max_jump_m = 3.0;       ///< |registered - predicted| position; valid (0, 1000]
  double max_jump_deg = 8.0;     ///< valid (0, 180]
  double max_position_sigma_m =
      1.0;  ///< sqrt of the largest eigenvalue of the xy covariance; valid (0, 1000]
  /// The map's other copy of the place (submap.max_path_m) aligns the scan elsewhere with at least
  /// this fraction of the tracked alignment's fit score: reported as ambiguous; valid [0, 1]
  /// (1 = only an equally good second copy; 0 = any alignment of the other copy).
  double ambiguity_fit_ratio = 0.8;
  /// Re-acquisition (check (h)): when the prediction's 3 sigma along its largest xy axis exceeds
  /// icp.inlier_distance_m (what tells two alignments apart), or its heading 3 sigma exceeds the
  /// ICP's heading capture range (icp.max_correspondence_m over submap.radius_m), the registration
  /// from the prediction is one local minimum among possibly several (after a degraded stretch
  /// along a wall, a wrong stretch of the same wall agrees with it). The scan is then also
  /// registered from up to this many starts on each side of the prediction along each wide axis,
  /// spaced by the ICP's capture range (icp.max_correspondence_m; in heading the capture range
  /// above) out to 3 sigma. The most probable alignment given the prediction (robust cost,
  /// IcpResult::cost, plus the prediction's Mahalanobis term) is kept; other alignments (> the
  /// inlier gate or 1 deg apart) whose cost the scan does not tell from it (rival_chi2) make it
  /// ambiguous: `degenerate`, with their spread (second moment about the kept one) added to its
  /// covariance. 0 = off; valid [0, 10].
  int reacquisition_starts = 2;
  /// Check (h)'s bound on a rival: 2 (cost - kept cost) / (icp.covariance_scale sigma^2) <= this, the
  /// likelihood ratio in the registration's calibrated units (= d^T Sigma^-1 d near the minimum).
  /// Check (g) (the fit profile, on when icp.profile_shift_m > 0) asks the same of the solution
  /// shifted by icp.profile_shift_m along its weakest direction (IcpResult::profile_chi2): within
  /// the bound the cost is flat there (a featureless wall, a row of look-alike posts) and the
  /// position along it is known only to about the shift, whatever sigma^2 H^-1 says. The scan is
  /// then `degenerate` (fused with the prediction) and its covariance gets profile_shift_m^2 along
  /// that direction.
  /// Not read from YAML: the localiser sets it to the chi^2(3) quantile of
  /// integrity.chi2_probability, the bound of its other checks (default: that of 0.999).
  double rival_chi2 = 16.266;
  /// Check (i), the map's agreement with itself around the anchor (the keyframe nearest to the
  /// registered pose, to which a client relates the pose: the Boreas-style output). A map that
  /// bends or folds between keyframes (a loop correction concentrated there, an odometry that
  /// stalled in a turn while the vehicle drove on) holds keyframes whose clouds do not sit where
  /// the rest of the submap says. Two tests, each failing when the difference d of two alignments
  /// exceeds the second alignment's own covariance (d^T Sigma^-1 d > rival_chi2):
  ///  - the scan, registered (from the tracked alignment) against the anchor keyframe's cloud
  ///    alone: that alignment gives the pose relative to the anchor, and uses a subset of the
  ///    submap's points, so its covariance bounds the variance of the difference;
  ///  - the anchor keyframe's own cloud, registered from its map pose against the other keyframes
  ///    within this path distance of it (reloc/map_connectivity.h; once per keyframe, cached).
  /// Either failing makes TrackResult::map_inconsistent. 0 = off; valid [0, 10000].
  double anchor_path_m = 20.0;

  /// The ICP's heading capture range: its correspondence gate (icp.max_correspondence_m) seen at
  /// the submap's radius, in radians. Two headings closer than this converge to one alignment.
  double headingCaptureRad() const { return icp.max_correspondence_m / submap.radius_m; }
};

/// Overrides from min_fit_score, min_inliers, max_rms_m, max_jump_m, max_jump_deg,
/// max_position_sigma_m and the sections submap:, icp: of `yaml`.
void loadParams(const YamlParams& yaml, MapTrackerParams& params);

struct TrackResult {
  bool accepted = false;
  std::string reason;  ///< why not (empty when accepted)
  /// Rejected only by max_position_sigma_m or the fit profile, check (g) (a weak direction, e.g. a
  /// corridor): every other test passed, so the registration can still be fused with a prediction
  /// (reloc/integrity.h).
  bool degenerate = false;
  IcpResult icp;
  bool submap_rebuilt = false;
  /// The tracked copy's keyframe nearest to the registered pose (position in map.keyframes): the
  /// next scan's anchor; -1 without a submap.
  long anchor = -1;
  /// A second copy of this place in the map (submap.max_path_m) also explains the scan, at
  /// `alternative`, at least ambiguity_fit_ratio as well: reported, the tracked copy kept.
  bool ambiguous = false;
  IcpResult alternative;
  /// The prediction was wide (check (h)): the scan was also registered from other starts.
  bool reacquisition = false;
  /// ... and another alignment within the prediction fitted almost as well (the scan is then
  /// `degenerate`, its covariance holding the alignments' spread).
  bool reacquisition_ambiguous = false;
  /// Check (i) (MapTrackerParams::anchor_path_m): d^T Sigma^-1 d of the scan's alignment against
  /// the anchor keyframe's cloud to the submap's, and of the anchor keyframe's own cloud registered
  /// against its neighbours to its map pose (-1 when not evaluated).
  double anchor_chi2 = -1, anchor_keyframe_chi2 = -1;
  /// ... either beyond rival_chi2: the map disagrees with itself here (not a rejection: the caller
  /// reports the pose with map_disagreement added to its covariance, and where the scan's test
  /// failed, the anchor's alignment).
  bool map_inconsistent = false;
  bool anchor_alignment_differs = false;                       ///< the scan's test failed
  Eigen::Matrix3d map_disagreement = Eigen::Matrix3d::Zero();  ///< sum of d d^T of the failed tests
  IcpResult anchor_alignment;  ///< the scan's alignment against the anchor keyframe's cloud
};

/// Two registrations of one scan are different alignments: farther apart than the inlier gate, or
/// more than 1 deg.
bool differentAlignments(const IcpResult& a, const IcpResult& b, const IcpParams& icp);

class MapTracker {
 public:
  /// Keeps a reference to `map` (must outlive this).
  MapTracker(const KeyframeMap& map, const MapTrackerParams& params = {});
  ~MapTracker();

  /// Registers `cloud` (sensor frame, motion compensated) near `predicted` (map frame), against
  /// the keyframes within submap.max_path_m of keyframe `anchor` along the map's graph (the copy
  /// being tracked: a global fix's keyframe, then each result's `anchor`); -1 = every keyframe near.
  /// With `predicted_cov` (the prediction's covariance) a wide prediction makes it a re-acquisition
  /// (MapTrackerParams::reacquisition_starts).
  TrackResult track(std::span<const RadarPoint> cloud, const mrpt::math::TPose2D& predicted, long anchor = -1,
                    const Eigen::Matrix3d* predicted_cov = nullptr);

  const MapTrackerParams& params() const { return params_; }

 private:
  void rebuild(const mrpt::math::TPose2D& predicted, long anchor);
  /// Check (i): the anchor keyframe against its neighbours (keyframeAgreement), and `thinned`
  /// registered against the anchor keyframe's cloud from out.icp's pose; fills out.anchor_chi2,
  /// anchor_keyframe_chi2, anchor_alignment, map_inconsistent, anchor_alignment_differs and
  /// map_disagreement.
  void checkAnchor(const std::vector<Eigen::Vector2d>& thinned, TrackResult& out);
  /// Check (i), the map's side: keyframe k's cloud against the other keyframes within
  /// anchor_path_m of it; the offset of its alignment from its map pose and that offset's chi^2.
  struct KeyframeAgreement {
    bool evaluated = false;
    double chi2 = -1;  ///< -1: too few points to tell
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  };
  const KeyframeAgreement& keyframeAgreement(std::size_t k);
  bool checksProfile() const { return params_.icp.profile_shift_m > 0; }  ///< check (g) on
  /// Check (h): registers the thinned scan from further starts along the prediction's wide axes;
  /// keeps the most probable alignment given the prediction in out.icp, flags an ambiguity and returns the
  /// rival alignments' spread (zero when there are none), which the caller adds to the covariance.
  Eigen::Matrix3d reacquire(const std::vector<Eigen::Vector2d>& thinned, const mrpt::math::TPose2D& predicted,
                            const Eigen::Matrix3d& predicted_cov, TrackResult& out) const;

  const KeyframeMap& map_;
  MapTrackerParams params_;
  MapConnectivity connectivity_;
  std::optional<LocalSubmap> submap_;
  std::optional<LocalSubmap> other_;  ///< keyframes near but beyond max_path_m: another copy
  long built_for_anchor_ = -1;
  std::optional<LocalSubmap> anchor_submap_;  ///< check (i): the anchor keyframe's cloud...
  long anchor_submap_for_ = -1;               ///< ... of this keyframe
  std::vector<KeyframeAgreement>
      agreement_;  ///< per keyframe (position in map.keyframes), filled on first use
};

}  // namespace radarslam
