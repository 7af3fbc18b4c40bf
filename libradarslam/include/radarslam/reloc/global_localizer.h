#pragma once
// Global localisation against a stored map with no initial guess (the "kidnapped robot" case):
// the M2DP descriptor of the scan's peak cloud (both PCA signs, loop/m2dp.h) retrieves the
// nearest map keyframes in descriptor space (top-k over ALL keyframes; exact linear search, which
// costs < 1 ms for thousands of keyframes), then each candidate is geometrically verified with
// loop/loop_verifier.h (no initial guess, uniqueness and overlap tests); the accepted candidate
// with the most inliers gives the pose: T_map_scan = T_map_keyframe (+) T_keyframe_scan.
// As in loop closure (paper Sec. III-C), but the database is the whole map.
#include <mrpt/math/TPose2D.h>

#include <span>
#include <vector>

#include "radarslam/loop/loop_verifier.h"
#include "radarslam/loop/m2dp.h"
#include "radarslam/map/keyframe_map.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

class YamlParams;

struct GlobalLocalizerParams {
  M2DPParams m2dp;                       ///< must match the map's descriptors (else recomputed)
  std::size_t candidates = 6;            ///< top-k within max_descriptor_distance, verified; valid [1, 1000]
  float max_descriptor_distance = 0.6f;  ///< retrieval radius (L2); valid (0, 100]
  std::size_t fallback_candidates =
      4;  ///< when none of those verifies: the nearest N beyond the radius; valid [0, 1000]
  bool recompute_descriptors = false;  ///< ignore the map's stored descriptors
  LoopVerifierParams verifier;
};

/// Overrides from the keys candidates, max_descriptor_distance, fallback_candidates,
/// recompute_descriptors and the sections m2dp:, verifier: of `yaml`.
void loadParams(const YamlParams& yaml, GlobalLocalizerParams& params);

/// A candidate the verifier refused only because another alignment of the keyframe's cloud scores
/// almost as well (LoopVerification::ambiguous_only): where the scan may be, in the map frame.
struct ContestedPlace {
  std::size_t keyframe = 0;  ///< index in map.keyframes
  /// T_map_keyframe (+) the verifier's alignment, then each of its rivals (LoopVerification::rivals)
  std::vector<mrpt::math::TPose2D> poses;
};

struct GlobalFix {
  bool found = false;
  mrpt::math::TPose2D pose;  ///< scan sensor pose in the map frame
  std::size_t keyframe = 0;  ///< index of the verified keyframe in map.keyframes
  float descriptor_distance = 0;
  LoopVerification verification;
  std::size_t verified = 0;  ///< candidates verified
  /// When no candidate was accepted: the verified ones refused only as ambiguous, in retrieval order.
  std::vector<ContestedPlace> contested;
};

/// A candidate keyframe and its descriptor distance.
struct RetrievedKeyframe {
  std::size_t keyframe = 0;
  float distance = 0;
};

class GlobalLocalizer {
 public:
  /// Keeps a reference to `map` (must outlive this). Keyframes without a usable descriptor (none
  /// stored, or another length than `params.m2dp` gives) get one computed from their cloud.
  GlobalLocalizer(const KeyframeMap& map, const GlobalLocalizerParams& params = {});

  /// The nearest `k` keyframes by descriptor distance over both PCA signs of `cloud`, best first.
  std::vector<RetrievedKeyframe> retrieve(std::span<const RadarPoint> cloud, std::size_t k) const;

  /// Retrieval + verification (see the file comment). `cloud` is the scan's peak cloud, sensor
  /// frame, motion compensated.
  GlobalFix localize(std::span<const RadarPoint> cloud) const;

  std::size_t descriptorsComputed() const { return computed_; }

 private:
  const KeyframeMap& map_;
  GlobalLocalizerParams params_;
  std::vector<M2DPDescriptor> descriptors_;      ///< per keyframe (empty = unusable)
  std::vector<std::vector<RadarPoint>> clouds_;  ///< per keyframe, as RadarPoint
  std::size_t computed_ = 0;
};

}  // namespace radarslam
