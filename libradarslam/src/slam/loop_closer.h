#pragma once
// Loop closing (paper Sec. III-C) for one keyframe after local mapping: M2DP retrieval from the
// kd-tree of earlier keyframes (recent ones excluded), geometric verification of the best
// candidates (loop/loop_verifier.h: global consensus search, ICP, uniqueness test), and for an
// accepted loop the pose-graph optimisation when the loop disagrees with the current estimate.
#include "loop_confirmation.h"
#include "loop_uncertainty.h"
#include "radarslam/loop/loop_detector.h"
#include "slam_state.h"

namespace radarslam::slam_detail {

class LoopCloser {
 public:
  LoopCloser(SlamState& state, const SlamParams& params);
  /// Searches loops for keyframe `id` (after local mapping inserted it), then adds it to the
  /// database. Keyframes must arrive in id order.
  void process(std::uint64_t id);
  /// Extending a map: adds keyframe `id` of the loaded map to the database (call in id order,
  /// before the first process()). Until the new session is anchored, its keyframes are matched
  /// against these only, without recency exclusion and without the drift gate.
  void addMapKeyframe(std::uint64_t id);

 private:
  /// Hands a loop refused as ambiguous only to confirmation_ and adds the loops it confirms to the
  /// graph (state locked); true when it added any, `optimise` set when one moves its query far.
  bool confirmPending(const PendingLoop& loop, bool& optimise);
  /// Withdraws confirmed loops (records) a unique loop contradicts: inactive in the graph, refused in
  /// the records (state locked); true when any.
  bool withdrawContradicted(const std::vector<std::size_t>& records);
  /// A loop's correction (dm metres, da radians) large enough to optimise the graph now.
  bool worthOptimising(double dm, double da) const;
  /// Moves the whole new session by the correction a verified loop to the map implies.
  void anchorSession(const TPose2D& implied_query_pose, std::uint64_t query);
  SlamState& state_;
  const SlamParams& params_;
  LoopDetector detector_;
  std::unique_ptr<LoopDetector> map_detector_;
  bool previous_closed_loop_ = false;
  DriftScaleEstimator drift_scale_;                 ///< the loaded map's keyframes (extending only)
  std::unique_ptr<LoopConfirmation> confirmation_;  ///< confirm_ambiguous_keyframes > 0
};

}  // namespace radarslam::slam_detail
