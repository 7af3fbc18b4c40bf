// Global localisation: M2DP retrieval over all map keyframes + geometric verification; see
// reloc/global_localizer.h.
#include "radarslam/reloc/global_localizer.h"

#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/reloc/submap_icp.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, GlobalLocalizerParams& p) {
  int k = static_cast<int>(p.candidates), fb = static_cast<int>(p.fallback_candidates);
  yaml.get("candidates", k, Range::closed(1, 1000));
  yaml.get("fallback_candidates", fb, Range::closed(0, 1000));
  yaml.get("max_descriptor_distance", p.max_descriptor_distance, Range::above(0, 100));
  yaml.get("recompute_descriptors", p.recompute_descriptors);
  p.candidates = static_cast<std::size_t>(k);
  p.fallback_candidates = static_cast<std::size_t>(fb);
  loadParams(yaml.section("m2dp"), p.m2dp);
  loadParams(yaml.section("verifier"), p.verifier);
}

GlobalLocalizer::GlobalLocalizer(const KeyframeMap& map, const GlobalLocalizerParams& params)
    : map_(map), params_(params) {
  params_.verifier.estimate_information = false;  // a global fix never uses the loop information
  const std::size_t expected_length = static_cast<std::size_t>(params.m2dp.azimuths * params.m2dp.elevations +
                                                               params.m2dp.rings * params.m2dp.sectors);
  descriptors_.reserve(map.keyframes.size());
  clouds_.reserve(map.keyframes.size());
  for (const auto& kf : map.keyframes) {
    clouds_.push_back(toRadarPoints(kf.points));
    if (!params.recompute_descriptors && kf.descriptor.size() == expected_length) {
      descriptors_.emplace_back(Eigen::Map<const Eigen::VectorXf>(
          kf.descriptor.data(), static_cast<Eigen::Index>(kf.descriptor.size())));
    } else {
      descriptors_.push_back(computeM2DP(clouds_.back(), params.m2dp));
      ++computed_;
    }
  }
}

std::vector<RetrievedKeyframe> GlobalLocalizer::retrieve(std::span<const RadarPoint> cloud,
                                                         std::size_t k) const {
  const M2DPDescriptor d0 = computeM2DP(cloud, params_.m2dp, false);
  const M2DPDescriptor d1 = computeM2DP(cloud, params_.m2dp, true);
  std::vector<RetrievedKeyframe> all;
  all.reserve(descriptors_.size());
  for (std::size_t i = 0; i < descriptors_.size(); ++i) {
    const float d = std::min(m2dpDistance(d0, descriptors_[i]), m2dpDistance(d1, descriptors_[i]));
    if (std::isfinite(d)) all.push_back({i, d});
  }
  const std::size_t n = std::min(k, all.size());
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n), all.end(),
                    [](const RetrievedKeyframe& a, const RetrievedKeyframe& b) {
                      return a.distance < b.distance || (a.distance == b.distance && a.keyframe < b.keyframe);
                    });
  all.resize(n);
  return all;
}

GlobalFix GlobalLocalizer::localize(std::span<const RadarPoint> cloud) const {
  GlobalFix best;
  const auto retrieved = retrieve(cloud, params_.candidates + params_.fallback_candidates);
  auto verifyRange = [&](std::size_t from, std::size_t to) {
    for (std::size_t r = from; r < to && r < retrieved.size(); ++r) {
      const auto& cand = retrieved[r];
      const LoopVerification v = verifyLoop(cloud, clouds_[cand.keyframe], params_.verifier);
      ++best.verified;
      double rival_m = 0, rival_deg = 0;
      for (const auto& rival : v.rivals) {
        rival_m = std::max(rival_m, std::hypot(rival.x, rival.y));
        rival_deg = std::max(rival_deg, std::abs(rival.phi) * 180 / M_PI);
      }
      logger().logFmt(mrpt::system::LVL_DEBUG,
                      "global: keyframe %zu distance %.3f: %s, inliers %zu ratio %.2f ambiguity %.2f (%zu "
                      "rivals, up to %.1f m / %.1f deg away)",
                      cand.keyframe, static_cast<double>(cand.distance),
                      v.accepted ? "accepted" : v.reason.c_str(), v.inliers, v.inlier_ratio,
                      v.ambiguity_ratio, v.rivals.size(), rival_m, rival_deg);
      const mrpt::poses::CPose2D pose =
          mrpt::poses::CPose2D(map_.keyframes[cand.keyframe].pose) + mrpt::poses::CPose2D(v.relative_pose);
      if (v.ambiguous_only) {
        ContestedPlace place{cand.keyframe, {pose.asTPose()}};
        for (const auto& rival : v.rivals)
          place.poses.push_back((pose + mrpt::poses::CPose2D(rival)).asTPose());
        best.contested.push_back(std::move(place));
      }
      if (!v.accepted) continue;
      if (!best.found || v.inliers > best.verification.inliers) {
        best.found = true;
        best.keyframe = cand.keyframe;
        best.descriptor_distance = cand.distance;
        best.verification = v;
        best.pose = pose.asTPose();
      }
    }
  };
  // Candidates within the retrieval radius, then (if none verified) the nearest ones beyond it.
  std::size_t in_radius = 0;
  while (in_radius < retrieved.size() && in_radius < params_.candidates &&
         retrieved[in_radius].distance <= params_.max_descriptor_distance)
    ++in_radius;
  verifyRange(0, in_radius);
  if (!best.found) verifyRange(in_radius, in_radius + params_.fallback_candidates);
  if (best.found) best.contested.clear();
  return best;
}

}  // namespace radarslam
