#pragma once
// Loop closing (paper Sec. III-C) for one keyframe after local mapping: M2DP retrieval from the
// kd-tree of earlier keyframes (recent ones excluded), geometric verification of the best
// candidates (loop/loop_verifier.h: global consensus search, ICP, uniqueness test), and for an
// accepted loop the pose-graph optimisation when the loop disagrees with the current estimate.
#include "loop_uncertainty.h"
#include "radarslam/loop/loop_detector.h"
#include "slam_state.h"

namespace radarslam::slam_detail {

class LoopCloser {
 public:
  LoopCloser(SlamState& state, const SlamParams& params)
      : state_(state), params_(params), detector_(params.loop_closing.detector) {}
  /// Searches loops for keyframe `id` (after local mapping inserted it), then adds it to the
  /// database. Keyframes must arrive in id order.
  void process(std::uint64_t id);
  /// Extending a map: adds keyframe `id` of the loaded map to the database (call in id order,
  /// before the first process()). Until the new session is anchored, its keyframes are matched
  /// against these only, without recency exclusion and without the drift gate.
  void addMapKeyframe(std::uint64_t id);

 private:
  /// Moves the whole new session by the correction a verified loop to the map implies.
  void anchorSession(const TPose2D& implied_query_pose, std::uint64_t query);
  SlamState& state_;
  const SlamParams& params_;
  LoopDetector detector_;
  std::unique_ptr<LoopDetector> map_detector_;
  bool previous_closed_loop_ = false;
  DriftScaleEstimator drift_scale_;  ///< the loaded map's keyframes (extending only)
};

}  // namespace radarslam::slam_detail
