#include "loop_proximity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace radarslam::slam_detail {

std::vector<LoopCandidate> proximityCandidates(const SlamState& state, std::uint64_t query,
                                               std::span<const M2DPDescriptor> descriptors,
                                               const LoopClosingParams& params,
                                               const std::function<double(std::uint64_t)>& bound_m) {
  const SlamKeyframe& q = state.keyframes.at(query);
  std::vector<std::pair<double, LoopCandidate>> near;
  for (std::uint64_t k = state.session_first; k < query; ++k) {
    const SlamKeyframe& kf = state.keyframes[k];
    if (kf.descriptor.size() == 0 || isRecent(params.detector, k, kf.travelled_m, query, q.travelled_m))
      continue;
    const double d = std::hypot(kf.pose.x - q.pose.x, kf.pose.y - q.pose.y);
    if (d > params.verifier.max_translation_m + bound_m(k)) continue;
    float distance = std::numeric_limits<float>::infinity();
    for (const auto& descriptor : descriptors)
      if (descriptor.size() == kf.descriptor.size())
        distance = std::min(distance, (descriptor - kf.descriptor).norm());
    near.emplace_back(d, LoopCandidate{static_cast<std::size_t>(k), distance});
  }
  std::stable_sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<LoopCandidate> out;
  for (std::size_t i = 0; i < near.size() && out.size() < params.detector.max_candidates; ++i)
    out.push_back(near[i].second);
  return out;
}

}  // namespace radarslam::slam_detail
