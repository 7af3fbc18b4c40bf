#pragma once
// Tracking against a stored map once localised: the scan's peak cloud is registered (robust ICP,
// reloc/submap_icp.h) against the local submap around the predicted pose (the previous map pose
// composed with the odometry motion T_prev_cur). The result is trusted only if it passes every
// test below; otherwise the caller must treat the scan as not localised.
#include <mrpt/math/TPose2D.h>

#include <optional>
#include <span>
#include <string>

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
};

/// Overrides from min_fit_score, min_inliers, max_rms_m, max_jump_m, max_jump_deg,
/// max_position_sigma_m and the sections submap:, icp: of `yaml`.
void loadParams(const YamlParams& yaml, MapTrackerParams& params);

struct TrackResult {
  bool accepted = false;
  std::string reason;  ///< why not (empty when accepted)
  /// Rejected only by max_position_sigma_m (a weak direction, e.g. a corridor): every other test
  /// passed, so the registration can still be fused with a prediction (reloc/integrity.h).
  bool degenerate = false;
  IcpResult icp;
  bool submap_rebuilt = false;
};

class MapTracker {
 public:
  /// Keeps a reference to `map` (must outlive this).
  MapTracker(const KeyframeMap& map, const MapTrackerParams& params = {});
  ~MapTracker();

  /// Registers `cloud` (sensor frame, motion compensated) near `predicted` (map frame).
  TrackResult track(std::span<const RadarPoint> cloud, const mrpt::math::TPose2D& predicted);

  const MapTrackerParams& params() const { return params_; }

 private:
  const KeyframeMap& map_;
  MapTrackerParams params_;
  std::optional<LocalSubmap> submap_;
};

}  // namespace radarslam
