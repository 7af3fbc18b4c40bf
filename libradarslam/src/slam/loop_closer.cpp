#include "loop_closer.h"

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <optional>

#include "graph_optimiser.h"
#include "loop_proximity.h"
#include "loop_uncertainty.h"
#include "radarslam/core/log.h"
#include "radarslam/core/se2_covariance.h"
#include "radarslam/loop/loop_verifier.h"

namespace radarslam::slam_detail {

LoopCloser::LoopCloser(SlamState& state, const SlamParams& params)
    : state_(state), params_(params), detector_(params.loop_closing.detector) {
  const LoopClosingParams& lc = params.loop_closing;
  if (lc.confirm_ambiguous_keyframes > 0)
    confirmation_ = std::make_unique<LoopConfirmation>(
        lc.confirm_ambiguous_keyframes, static_cast<std::uint64_t>(lc.confirm_max_gap_keyframes),
        params.pose_graph.loop_chi2_gate);
}

void LoopCloser::addMapKeyframe(std::uint64_t id) {
  if (!map_detector_) {
    LoopDetectorParams p = params_.loop_closing.detector;
    p.exclude_recent = 0;
    p.exclude_recent_distance_m = 0;
    map_detector_ = std::make_unique<LoopDetector>(p);
  }
  const SlamKeyframe& kf = state_.keyframes.at(id);
  map_detector_->add(kf.descriptor, kf.travelled_m);
  detector_.add(kf.descriptor, kf.travelled_m);
}

void LoopCloser::anchorSession(const TPose2D& implied, std::uint64_t query) {
  const TPose2D& q = state_.keyframes[query].pose;
  const TPose2D correction = compose(implied, between(q, TPose2D(0, 0, 0)));  // implied (+) q^-1
  for (std::size_t i = state_.session_first; i < state_.keyframes.size(); ++i)
    state_.keyframes[i].pose = compose(correction, state_.keyframes[i].pose);
  for (auto& mp : state_.points)
    if (mp.reference >= state_.session_first) mp.xy = transformPoint(correction, mp.xy);
  state_.anchored = true;
  state_.anchor_keyframe = query;
  state_.anchor_travelled_m = state_.keyframes[query].travelled_m;
  ++state_.corrections;
  logger().logFmt(mrpt::system::LVL_INFO, "slam: new session anchored to the map at keyframe %llu",
                  static_cast<unsigned long long>(query));
}

bool LoopCloser::withdrawContradicted(const std::vector<std::size_t>& records) {
  for (const std::size_t r : records) {
    for (AcceptedLoop& l : state_.loops)
      if (l.record == r) l.active = false;
    LoopRecord& rec = state_.records[r];
    rec.accepted = rec.confirmed = false;
    rec.reason = "withdrawn: a unique loop of a nearby keyframe places it elsewhere";
    --state_.stats.loops_accepted;
    --state_.stats.loops_confirmed;
    ++state_.stats.loops_rejected;
    ++state_.stats.confirmations_withdrawn;
    logger().logFmt(mrpt::system::LVL_DEBUG, "slam: confirmed loop %llu -> %llu withdrawn",
                    static_cast<unsigned long long>(rec.match), static_cast<unsigned long long>(rec.query));
  }
  return !records.empty();
}

bool LoopCloser::worthOptimising(double dm, double da) const {
  const LoopClosingParams& lc = params_.loop_closing;
  return dm > lc.optimise_min_correction_m || da > lc.optimise_min_correction_deg * M_PI / 180;
}

bool LoopCloser::confirmPending(const PendingLoop& loop, bool& optimise) {
  const auto confirmed = confirmation_->add(loop, [&](std::uint64_t k) { return state_.keyframes[k].pose; });
  for (const PendingLoop& c : confirmed) {
    LoopRecord& rec = state_.records[c.record];
    rec.accepted = rec.confirmed = true;
    rec.reason.clear();
    --state_.stats.loops_rejected;
    ++state_.stats.loops_accepted;
    ++state_.stats.loops_confirmed;
    const TPose2D implied = compose(state_.keyframes[c.match].pose, c.relative);
    const TPose2D& q = state_.keyframes[c.query].pose;
    optimise |= worthOptimising(std::hypot(implied.x - q.x, implied.y - q.y),
                                std::abs(std::remainder(implied.phi - q.phi, 2 * M_PI)));
    state_.loops.push_back(AcceptedLoop{c.match, c.query, c.relative, c.information, c.record, true});
    logger().logFmt(mrpt::system::LVL_DEBUG, "slam: ambiguous loop %llu -> %llu confirmed",
                    static_cast<unsigned long long>(c.match), static_cast<unsigned long long>(c.query));
  }
  state_.stats.confirmations_held_back = confirmation_->rivalled();
  return !confirmed.empty();
}

void LoopCloser::process(std::uint64_t id) {
  const auto t0 = std::chrono::steady_clock::now();
  std::shared_ptr<const std::vector<RadarPoint>> cloud;
  std::vector<M2DPDescriptor> descriptors;
  double travelled = 0;
  bool anchored = true;
  {
    std::lock_guard lock(state_.mutex);
    anchored = state_.anchored;
    const SlamKeyframe& kf = state_.keyframes.at(id);
    cloud = kf.cloud;
    descriptors = {kf.descriptor, kf.descriptor_flipped};
    travelled = kf.travelled_m;
  }
  const auto& lc = params_.loop_closing;
  const bool gate = lc.drift_fraction > 0 && anchored;
  const bool chi2_gate = gate && lc.drift_gate_chi2 > 0;
  // The linear drift bound between keyframe `m` and the query (see LoopClosingParams).
  auto driftBound = [&](std::uint64_t m) {
    // To a keyframe of a loaded map: the new session has drifted since it was anchored.
    const double d =
        travelled - (m < state_.session_first ? state_.anchor_travelled_m : state_.keyframes[m].travelled_m);
    return std::pair(lc.drift_base_m + lc.drift_fraction * d,
                     (lc.drift_base_deg + lc.drift_deg_per_m * d) * M_PI / 180);
  };
  std::optional<ChainCovariance> chain;
  // The accumulated odometry covariance of the query in m's frame (chi2 gate). To a keyframe of a
  // loaded map: the chain since the session was anchored, turned into m's frame.
  auto chainCovarianceTo = [&](std::uint64_t m) -> Eigen::Matrix3d {
    if (m >= state_.session_first) return chain->relativeTo(m);
    const std::uint64_t a = state_.anchor_keyframe;
    return rotateCovariance(chain->relativeTo(a),
                            state_.keyframes[a].pose.phi - state_.keyframes[m].pose.phi);
  };
  bool optimise = false, closed = false;
  if ((params_.loop_closing.enabled || !anchored) && descriptors[0].size() > 0) {
    auto candidates =
        anchored ? detector_.query(descriptors, travelled) : map_detector_->query(descriptors, travelled);
    bool by_proximity = false;  // then the candidates are within the linear bound already
    if (candidates.empty() && gate && lc.proximity_candidates) {
      std::lock_guard lock(state_.mutex);
      by_proximity = true;
      candidates = proximityCandidates(state_, id, descriptors, lc,
                                       [&](std::uint64_t m) { return driftBound(m).first; });
      state_.stats.proximity_candidates += candidates.size();
    }
    if (chi2_gate && !candidates.empty()) {
      std::lock_guard lock(state_.mutex);
      std::uint64_t first = id;
      for (const auto& c : candidates)
        first = std::min(first, c.keyframe >= state_.session_first ? c.keyframe : state_.anchor_keyframe);
      chain.emplace(state_, first, id, params_.odometry_edges);
    }
    if (gate && (chi2_gate || !by_proximity)) {
      std::lock_guard lock(state_.mutex);
      const TPose2D& q = state_.keyframes[id].pose;
      std::erase_if(candidates, [&](const LoopCandidate& c) {
        const TPose2D& m = state_.keyframes[c.keyframe].pose;
        double bound = driftBound(c.keyframe).first;
        if (chi2_gate) {  // the chi2 ellipse's largest position semi-axis, plus the loop's own floor
          const Eigen::Matrix2d pos = chainCovarianceTo(c.keyframe).topLeftCorner<2, 2>();
          const double var = pos.allFinite() ? pos.eigenvalues().real().maxCoeff() : 1e18;
          bound = std::sqrt(lc.drift_gate_chi2 *
                            (state_.odometry_variance_scale * var + lc.loop_sigma_xy_m * lc.loop_sigma_xy_m));
        }
        return std::hypot(q.x - m.x, q.y - m.y) > lc.verifier.max_translation_m + bound;
      });
    }
    const std::size_t n = std::min<std::size_t>(
        candidates.size(), previous_closed_loop_ ? lc.max_verifications_after_loop : lc.max_verifications);
    // The alignment's information is only used when the graph is given it (loopInformation).
    LoopVerifierParams verifier = lc.verifier;
    verifier.estimate_information = lc.loop_information_estimated;
    for (std::size_t c = 0; c < n; ++c) {
      std::shared_ptr<const std::vector<RadarPoint>> match_cloud;
      {
        std::lock_guard lock(state_.mutex);
        match_cloud = state_.keyframes.at(candidates[c].keyframe).cloud;
      }
      const LoopVerification v = verifyLoop(*cloud, *match_cloud, verifier);
      std::lock_guard lock(state_.mutex);
      const std::uint64_t match = candidates[c].keyframe;
      const TPose2D& q = state_.keyframes[id].pose;
      const TPose2D estimated = between(state_.keyframes[match].pose, q);
      std::optional<Eigen::Matrix3d> chain_cov;
      if (chi2_gate) chain_cov = chainCovarianceTo(match);
      // The drift gate for a relative pose `rel` of the query in match's frame with information
      // `information`: the correction it implies (a partial loop: only across its line) and whether
      // it is within the bound (linear, or chi^2 under the scaled chain covariance).
      struct Gate {
        bool pass = true;
        double dm = 0, da = 0, d2 = 0;
      };
      auto driftGate = [&](const TPose2D& rel, const Eigen::Matrix3d& information,
                           const Eigen::Vector2d* slide_direction) {
        Gate g;
        const TPose2D implied = compose(state_.keyframes[match].pose, rel);
        Eigen::Vector2d correction(implied.x - q.x, implied.y - q.y);
        if (slide_direction) correction = acrossLine(correction, *slide_direction, implied.phi);
        g.dm = correction.norm();
        g.da = std::abs(std::remainder(implied.phi - q.phi, 2 * M_PI));
        if (chi2_gate) {
          g.d2 = correctionMahalanobis2(rel, estimated, state_.odometry_variance_scale * *chain_cov,
                                        information);
          g.pass = g.d2 <= lc.drift_gate_chi2;
        } else if (gate) {
          const auto [bound_m, bound_rad] = driftBound(match);
          g.pass = g.dm <= bound_m && g.da <= bound_rad;
        }
        return g;
      };
      LoopRecord rec;
      rec.query = id;
      rec.match = match;
      rec.descriptor_distance = candidates[c].distance;
      rec.relative = v.relative_pose;
      rec.inlier_ratio = v.inlier_ratio;
      rec.ambiguity_ratio = v.ambiguity_ratio;
      rec.information = loopInformation(v.information, lc);  // what the pose graph is given
      // Ambiguous only through rivals the drift gate would refuse anyway: unique where the loop can be.
      const bool unique_within_bound =
          gate && lc.ambiguity_within_drift_bound && uniqueWithinGate(v, [&](const TPose2D& rel) {
            return driftGate(rel, rec.information, nullptr).pass;
          });
      // A partial loop: ambiguous only along one line, every other test passed (accept_slide_loops).
      rec.slide = !v.accepted && !unique_within_bound && v.ambiguous_only && v.slide &&
                  lc.accept_slide_loops && anchored;
      rec.accepted = v.accepted || unique_within_bound || rec.slide;
      rec.reason = rec.accepted ? "" : v.reason;
      if (rec.slide) {
        rec.slide_direction = v.slide_direction;
        rec.information = slideLoopInformation(rec.information, v.slide_direction);
      }
      ++state_.stats.loop_candidates;
      const TPose2D implied = compose(state_.keyframes[match].pose, v.relative_pose);
      const Eigen::Matrix3d& loop_information = rec.information;
      if (rec.accepted && chi2_gate && !rec.slide)  // the scale's chi^2(3) model is of full loops
        drift_scale_.add(correctionMahalanobis2(v.relative_pose, estimated, *chain_cov, loop_information));
      if (chi2_gate) state_.odometry_variance_scale = drift_scale_.scale();
      const Gate g = driftGate(v.relative_pose, loop_information, rec.slide ? &rec.slide_direction : nullptr);
      const double dm = g.dm, da = g.da;
      if (rec.accepted && !g.pass) {
        rec.accepted = false;
        rec.reason = "beyond the drift bound (" + std::to_string(dm) + " m" +
                     (chi2_gate ? ", chi2 " + std::to_string(g.d2) : std::string()) + ")";
        rec.slide = false;
      }
      state_.records.push_back(rec);
      if (!state_.records.back().accepted) {
        ++state_.stats.loops_rejected;
        // Refused only as an ambiguous place: a loop once the next keyframes agree with it. A place
        // that looks alike elsewhere needs the prior more than a unique one: its correction must be
        // within the drift bound of the shortest path through the graph (accepted loops as
        // shortcuts), not of the distance driven between the two keyframes.
        auto withinPathBound = [&] {
          if (!gate) return true;
          const double path = graphPathLength(state_, match, id);
          return g.dm <= lc.drift_base_m + lc.drift_fraction * path &&
                 g.da <= (lc.drift_base_deg + lc.drift_deg_per_m * path) * M_PI / 180;
        };
        // A placement beyond the bounds still counts as a rival if the next keyframes agree on it.
        if (confirmation_ && anchored && v.ambiguous_only && !rec.slide)
          closed |= confirmPending({id, match, v.relative_pose, loop_information, state_.records.size() - 1,
                                    g.pass && withinPathBound()},
                                   optimise);
        continue;
      }
      ++state_.stats.loops_accepted;
      // A unique place: ambiguous loops of nearby keyframes that agree with it enter with it, and
      // ones confirmed earlier that contradict it are withdrawn.
      if (confirmation_ && state_.anchored && !rec.slide)
        optimise |= withdrawContradicted(confirmation_->addUnique(
            {id, match, v.relative_pose, loop_information, state_.records.size() - 1},
            [&](std::uint64_t k) { return state_.keyframes[k].pose; }));
      if (!state_.anchored) anchorSession(implied, id);
      AcceptedLoop loop{rec.match, id, v.relative_pose, loop_information, state_.records.size() - 1, true};
      optimise |= worthOptimising(dm, da);
      logger().logFmt(mrpt::system::LVL_DEBUG,
                      "slam: loop %llu -> %llu accepted (inliers %.2f, correction %.2f m)",
                      static_cast<unsigned long long>(loop.from), static_cast<unsigned long long>(loop.to),
                      v.inlier_ratio, dm);
      state_.loops.push_back(loop);
      closed = true;
    }
  }
  previous_closed_loop_ = closed;
  detector_.add(descriptors[0], travelled);
  if (optimise) optimiseAndCorrect(state_, params_);
  std::lock_guard lock(state_.mutex);
  state_.stats.loop_closing_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace radarslam::slam_detail
