#pragma once
// Is a street driven twice one street in the map? (issue 13, item 6; for reports and tests, SLAM
// never needs it.) For every pair of map keyframes whose ground-truth positions are within
// pair_distance_m, the relative pose in the map is compared with the ground-truth relative pose; a
// pair is consistent when it is within max_error_m and max_error_deg. "Revisit" pairs are those
// separated by at least revisit_gap_m of ground-truth path (the place was left and came back to):
// those are what loop closure must get right; near-consecutive pairs only test the odometry.
#include <cstddef>

#include "radarslam/core/trajectory.h"
#include "radarslam/map/keyframe_map.h"

namespace radarslam {

struct MapConsistencyParams {
  double pair_distance_m = 10.0;
  double revisit_gap_m = 50.0;
  double max_error_m = 0.3;
  double max_error_deg = 0.5;
};

struct PairConsistency {
  std::size_t pairs = 0, consistent = 0;
  double fraction = 1.0;  ///< consistent / pairs (1 when there are no pairs)
  double median_error_m = 0, worst_error_m = 0, worst_error_deg = 0;
};

struct MapConsistency {
  PairConsistency revisits;  ///< pairs at least revisit_gap_m of path apart
  PairConsistency all;       ///< every pair within pair_distance_m
};

MapConsistency evaluateMapConsistency(const KeyframeMap& map, const Trajectory& ground_truth,
                                      const MapConsistencyParams& params = {});

}  // namespace radarslam
