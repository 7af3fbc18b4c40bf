#pragma once
// Loop-closure candidate retrieval (paper Sec. III-C): a database of keyframe M2DP descriptors in
// a kd-tree (nanoflann); a query returns the nearest keyframes within a descriptor distance,
// skipping the recent keyframes (by index window and by travelled distance) that are trivially
// similar to the query. Revisits in the opposite direction are found because M2DP is rotation
// invariant (the PCA frame turns with the cloud).
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "radarslam/loop/m2dp.h"

namespace radarslam {

class YamlParams;

struct LoopDetectorParams {
  float max_descriptor_distance = 0.45f;  ///< candidates must be closer than this (L2); valid (0, 100]
  std::size_t max_candidates = 5;         ///< top-k; valid [1, 1000]
  std::size_t exclude_recent = 30;        ///< never return the last N keyframes; valid [0, 1000000]
  double exclude_recent_distance_m =
      50;  ///< nor keyframes driven less than this before the query; valid [0, 1000000]
};

/// Overrides `params` from max_descriptor_distance, max_candidates, exclude_recent,
/// exclude_recent_distance_m.
void loadParams(const YamlParams& yaml, LoopDetectorParams& params);

/// True when `keyframe` is too recent to be a loop candidate of the query keyframe number `query`
/// (insertion order; the query comes after every earlier keyframe): one of the last
/// exclude_recent keyframes before it, or driven less than exclude_recent_distance_m before it.
inline bool isRecent(const LoopDetectorParams& params, std::size_t keyframe, double keyframe_travelled_m,
                     std::size_t query, double query_travelled_m) {
  return keyframe + params.exclude_recent >= query ||
         query_travelled_m - keyframe_travelled_m < params.exclude_recent_distance_m;
}

struct LoopCandidate {
  std::size_t keyframe = 0;  ///< index in insertion order
  float distance = 0;        ///< descriptor distance
};

class LoopDetector {
 public:
  explicit LoopDetector(const LoopDetectorParams& params = {});
  ~LoopDetector();
  LoopDetector(const LoopDetector&) = delete;
  LoopDetector& operator=(const LoopDetector&) = delete;

  /// Adds keyframe number size() with its descriptor and the distance driven since the start
  /// (odometry arc length, non-decreasing). An empty descriptor is stored but never returned.
  /// Throws std::invalid_argument if the descriptor length differs from the first one.
  std::size_t add(const M2DPDescriptor& descriptor, double travelled_m);

  /// Candidates for a query at travelled distance `travelled_m` (the query is not in the
  /// database yet), best first. Every descriptor in `descriptors` is searched (e.g. both PCA
  /// signs), each keyframe is reported once with its smallest distance.
  std::vector<LoopCandidate> query(std::span<const M2DPDescriptor> descriptors, double travelled_m) const;
  std::vector<LoopCandidate> query(const M2DPDescriptor& descriptor, double travelled_m) const {
    return query(std::span<const M2DPDescriptor>(&descriptor, 1), travelled_m);
  }

  std::size_t size() const;
  const LoopDetectorParams& params() const { return params_; }

 private:
  struct Impl;
  LoopDetectorParams params_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radarslam
