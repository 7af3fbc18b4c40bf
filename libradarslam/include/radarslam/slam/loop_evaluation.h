#pragma once
// Scoring loop closures against ground truth (for reports and tests; SLAM never needs it).
//  - A keyframe "has a true loop" if an earlier keyframe, outside the detector's exclusion (at
//    least exclude_recent keyframes and exclude_recent_distance_m of ground-truth path before
//    it), lies within true_loop_distance_m.
//  - Recall = keyframes with a true loop for which an accepted, correct loop was found / keyframes
//    with a true loop.
//  - An accepted loop is false if its relative pose is more than max_error_m or max_error_deg
//    from the ground-truth relative pose of the two keyframes (a correct relative pose between
//    keyframes farther apart than true_loop_distance_m is still a valid loop).
//  - A refused candidate is judged the same way: right (the verifier's relative pose was within
//    those bounds; a loop lost) or wrong (refusing it was right), counted by why it was refused.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "radarslam/core/trajectory.h"
#include "radarslam/map/keyframe_map.h"
#include "radarslam/slam/radar_slam.h"

namespace radarslam {

struct LoopEvaluationParams {
  double true_loop_distance_m = 6.0;
  std::size_t exclude_recent = 30;
  double exclude_recent_distance_m = 50.0;
  double max_error_m = 2.0;
  double max_error_deg = 3.0;
};

struct LoopEvaluation {
  std::size_t keyframes_evaluated = 0;  ///< keyframes with a ground-truth pose
  std::size_t keyframes_with_true_loop = 0, keyframes_with_loop_found = 0;
  std::size_t accepted = 0, false_accepted = 0;  ///< by verification (before the graph's test)
  std::size_t false_in_graph = 0;                ///< false loops still active after optimisation
  double recall = 0;
  double max_error_m = 0, max_error_deg = 0;  ///< over correct accepted loops
  /// Consistency of the verifier's information over correct accepted loops: NEES = e^T I e of the
  /// (x, y, phi) error; a calibrated estimate has mean 3 and 95 % within chi2(3) 95 % = 7.81.
  double nees_mean = 0, nees_within_95 = 0;
  /// Partial loops (LoopRecord::slide), judged only on what they constrain (the offset across their
  /// line and the heading); a false one also counts in false_accepted / false_in_graph. They count
  /// in neither the recall nor the error and NEES figures above.
  std::size_t slide_accepted = 0, slide_false = 0;
  /// Ambiguous places confirmed by the next keyframes (LoopRecord::confirmed), and how many false.
  std::size_t confirmed_accepted = 0, confirmed_false = 0;
  /// Refused candidates judged like accepted loops: `refused_right` had a relative pose within
  /// max_error_m / max_error_deg of the truth (a loop the system could have used), by the reason it
  /// was refused (LoopRecord::reason up to its first " (", e.g. "ambiguous place"); `refused_wrong`
  /// had not (refusing them was right).
  std::map<std::string, std::size_t> refused_right;
  std::size_t refused_wrong = 0;
};

/// "N reason, M reason" of LoopEvaluation::refused_right ("none" when empty).
std::string refusedRightText(const LoopEvaluation& evaluation);

LoopEvaluation evaluateLoops(const KeyframeMap& map, const std::vector<LoopRecord>& loops,
                             const Trajectory& ground_truth, const LoopEvaluationParams& params = {});

}  // namespace radarslam
