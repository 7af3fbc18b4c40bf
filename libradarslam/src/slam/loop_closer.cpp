#include "loop_closer.h"

#include <chrono>
#include <cmath>

#include "graph_optimiser.h"
#include "radarslam/core/log.h"
#include "radarslam/loop/loop_verifier.h"

namespace radarslam::slam_detail {

void LoopCloser::process(std::uint64_t id) {
  const auto t0 = std::chrono::steady_clock::now();
  std::shared_ptr<const std::vector<RadarPoint>> cloud;
  std::vector<M2DPDescriptor> descriptors;
  double travelled = 0;
  {
    std::lock_guard lock(state_.mutex);
    const SlamKeyframe& kf = state_.keyframes.at(id);
    cloud = kf.cloud;
    descriptors = {kf.descriptor, kf.descriptor_flipped};
    travelled = kf.travelled_m;
  }
  const auto& lc = params_.loop_closing;
  const bool gate = lc.drift_fraction > 0;
  // The drift bound between keyframe `m` and the query (see LoopClosingParams).
  auto driftBound = [&](std::uint64_t m) {
    const double d = travelled - state_.keyframes[m].travelled_m;
    return std::pair(lc.drift_base_m + lc.drift_fraction * d, (lc.drift_base_deg + lc.drift_deg_per_m * d) * M_PI / 180);
  };
  bool optimise = false;
  if (params_.loop_closing.enabled && descriptors[0].size() > 0) {
    auto candidates = detector_.query(descriptors, travelled);
    if (gate) {
      std::lock_guard lock(state_.mutex);
      const TPose2D& q = state_.keyframes[id].pose;
      std::erase_if(candidates, [&](const LoopCandidate& c) {
        const TPose2D& m = state_.keyframes[c.keyframe].pose;
        return std::hypot(q.x - m.x, q.y - m.y) > lc.verifier.max_translation_m + driftBound(c.keyframe).first;
      });
    }
    const std::size_t n = std::min<std::size_t>(candidates.size(), lc.max_verifications);
    for (std::size_t c = 0; c < n; ++c) {
      std::shared_ptr<const std::vector<RadarPoint>> match_cloud;
      {
        std::lock_guard lock(state_.mutex);
        match_cloud = state_.keyframes.at(candidates[c].keyframe).cloud;
      }
      const LoopVerification v = verifyLoop(*cloud, *match_cloud, params_.loop_closing.verifier);
      LoopRecord rec;
      rec.query = id;
      rec.match = candidates[c].keyframe;
      rec.descriptor_distance = candidates[c].distance;
      rec.accepted = v.accepted;
      rec.reason = v.reason;
      rec.relative = v.relative_pose;
      rec.inlier_ratio = v.inlier_ratio;
      rec.ambiguity_ratio = v.ambiguity_ratio;
      std::lock_guard lock(state_.mutex);
      ++state_.stats.loop_candidates;
      state_.records.push_back(rec);
      // Where the loop puts the query vs. where the estimate has it.
      const TPose2D implied = compose(state_.keyframes[rec.match].pose, v.relative_pose);
      const TPose2D& q = state_.keyframes[id].pose;
      const double dm = std::hypot(implied.x - q.x, implied.y - q.y);
      const double da = std::abs(std::remainder(implied.phi - q.phi, 2 * M_PI));
      if (v.accepted && gate) {
        const auto [bound_m, bound_rad] = driftBound(rec.match);
        if (dm > bound_m || da > bound_rad) {
          state_.records.back().accepted = false;
          state_.records.back().reason = "beyond the drift bound (" + std::to_string(dm) + " m)";
        }
      }
      if (!state_.records.back().accepted) {
        ++state_.stats.loops_rejected;
        continue;
      }
      ++state_.stats.loops_accepted;
      AcceptedLoop loop{rec.match, id, v.relative_pose, v.information, state_.records.size() - 1, true};
      optimise |= dm > lc.optimise_min_correction_m || da > lc.optimise_min_correction_deg * M_PI / 180;
      logger().logFmt(mrpt::system::LVL_DEBUG, "slam: loop %llu -> %llu accepted (inliers %.2f, correction %.2f m)",
                      static_cast<unsigned long long>(loop.from), static_cast<unsigned long long>(loop.to),
                      v.inlier_ratio, dm);
      state_.loops.push_back(loop);
    }
  }
  detector_.add(descriptors[0], travelled);
  if (optimise) optimiseAndCorrect(state_, params_);
  std::lock_guard lock(state_.mutex);
  state_.stats.loop_closing_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace radarslam::slam_detail
