#pragma once
// Map growth with area, not drive time (issue 16 item 5): before a map is saved, a keyframe is
// dropped when an earlier keyframe of another pass already covers its place. The radar sees 360
// degrees, so coverage is position only: a street driven back the other way is the same place.
//
//   keyframe i is redundant when a kept keyframe j (earlier in map order, i.e. driving order)
//   lies within coverage_radius_m of it and at least min_path_gap_m of driven path before it (a
//   different pass, not the previous keyframes of the same one).
//
// The pose graph stays connected and keeps the cross-pass constraints: a run of dropped keyframes
// between two kept ones becomes one odometry edge (relative poses composed, covariances compounded
// with SE(2) Jacobians); a loop edge to a dropped keyframe moves to the kept keyframe that covers
// it, its relative pose taken from the (optimised) map poses. Map points lose the dropped
// observers and disappear with the last one.
#include <cstddef>

#include "radarslam/map/keyframe_map.h"

namespace radarslam {

struct KeyframeCullingParams {
  bool enabled = true;
  /// The odometry makes a keyframe every 2 m (frontend keyframe rule); a revisit in the next lane
  /// (~1.5 m over) has an earlier keyframe within this distance; valid (0, 1000]
  double coverage_radius_m = 2.5;
  /// Path driven between the covering keyframe and the redundant one; valid [0, 1e6]
  double min_path_gap_m = 50.0;
};

struct CullingReport {
  std::size_t keyframes_before = 0, keyframes_after = 0;
  std::size_t edges_before = 0, edges_after = 0;
  std::size_t points_before = 0, points_after = 0;
};

/// Drops the redundant keyframes of `map` in place (nothing when !params.enabled).
CullingReport cullRedundantKeyframes(KeyframeMap& map, const KeyframeCullingParams& params);

}  // namespace radarslam
