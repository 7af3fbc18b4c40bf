#pragma once
// Loop candidates by proximity (ours; LoopClosingParams::proximity_candidates): where the M2DP
// search returns nothing, the keyframes that the drift gate would let through anyway — driven at
// least detector.exclude_recent_distance_m before the query (and not among the last
// detector.exclude_recent keyframes), and in the current map within verifier.max_translation_m +
// the drift bound of the query — nearest first. The pose graph says where a revisit can be; the
// verifier (uniqueness, overlap) and the drift gate then judge it as any other candidate.
#include <functional>
#include <span>
#include <vector>

#include "radarslam/loop/loop_detector.h"
#include "radarslam/loop/m2dp.h"
#include "slam_state.h"

namespace radarslam::slam_detail {

/// At most detector.max_candidates of this session's keyframes (from state.session_first) before
/// `query`, nearest in the map first; `bound_m(k)` = the drift bound between keyframe k and the
/// query. Each candidate's `distance` is its smallest M2DP distance to `descriptors` (infinity when
/// none compares). Keyframes without a descriptor are skipped. The caller holds state.mutex.
std::vector<LoopCandidate> proximityCandidates(const SlamState& state, std::uint64_t query,
                                               std::span<const M2DPDescriptor> descriptors,
                                               const LoopClosingParams& params,
                                               const std::function<double(std::uint64_t)>& bound_m);

}  // namespace radarslam::slam_detail
