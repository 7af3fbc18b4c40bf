#include "radarslam/slam/loop_evaluation.h"

#include <cmath>
#include <optional>

#include "slam_state.h"

namespace radarslam {

using slam_detail::between;

LoopEvaluation evaluateLoops(const KeyframeMap& map, const std::vector<LoopRecord>& loops,
                             const Trajectory& gt, const LoopEvaluationParams& p) {
  LoopEvaluation ev;
  const std::size_t n = map.keyframes.size();
  std::vector<std::optional<mrpt::math::TPose2D>> truth(n);
  std::vector<double> travelled(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    truth[i] = interpolatePose(gt, map.keyframes[i].stamp_ns);
    ev.keyframes_evaluated += truth[i].has_value();
    if (i > 0) {
      travelled[i] = travelled[i - 1];
      if (truth[i] && truth[i - 1])
        travelled[i] += std::hypot(truth[i]->x - truth[i - 1]->x, truth[i]->y - truth[i - 1]->y);
    }
  }
  std::vector<char> has_true(n, 0), found(n, 0);
  std::size_t nees_count = 0, nees_inside = 0;
  for (std::size_t q = 0; q < n; ++q) {
    if (!truth[q]) continue;
    for (std::size_t k = 0; k + p.exclude_recent < q; ++k) {
      if (!truth[k] || travelled[q] - travelled[k] < p.exclude_recent_distance_m) continue;
      if (std::hypot(truth[k]->x - truth[q]->x, truth[k]->y - truth[q]->y) < p.true_loop_distance_m) {
        has_true[q] = 1;
        break;
      }
    }
  }
  for (const auto& l : loops) {  // refused candidates: a loop lost, or rightly refused
    if (l.accepted || l.query >= n || l.match >= n || !truth[l.query] || !truth[l.match]) continue;
    const auto g = between(*truth[l.match], *truth[l.query]);
    const double em = std::hypot(l.relative.x - g.x, l.relative.y - g.y);
    const double ed = std::abs(std::remainder(l.relative.phi - g.phi, 2 * M_PI)) * 180 / M_PI;
    if (em > p.max_error_m || ed > p.max_error_deg)
      ++ev.refused_wrong;
    else
      ++ev.refused_right[l.reason.substr(0, l.reason.find(" ("))];
  }
  for (const auto& l : loops) {
    if (!l.accepted || l.query >= n || l.match >= n || !truth[l.query] || !truth[l.match]) continue;
    ++ev.accepted;
    const auto g = between(*truth[l.match], *truth[l.query]);
    Eigen::Vector2d et(l.relative.x - g.x, l.relative.y - g.y);                        // in the match's frame
    if (l.slide) et = slam_detail::acrossLine(et, l.slide_direction, l.relative.phi);  // only across
    const double em = et.norm();
    const double ed = std::abs(std::remainder(l.relative.phi - g.phi, 2 * M_PI)) * 180 / M_PI;
    const bool wrong = em > p.max_error_m || ed > p.max_error_deg;
    if (wrong) {
      ++ev.false_accepted;
      ev.false_in_graph += !l.rejected_by_graph;
    }
    if (l.confirmed) {
      ++ev.confirmed_accepted;
      ev.confirmed_false += wrong;
    }
    if (l.slide) {
      ++ev.slide_accepted;
      ev.slide_false += wrong;
    }
    if (wrong || l.slide) continue;
    const Eigen::Vector3d e(l.relative.x - g.x, l.relative.y - g.y,
                            std::remainder(l.relative.phi - g.phi, 2 * M_PI));
    const double nees = e.dot(l.information * e);
    ev.nees_mean += nees;
    ++nees_count;
    nees_inside += nees <= 7.815;
    ev.max_error_m = std::max(ev.max_error_m, em);
    ev.max_error_deg = std::max(ev.max_error_deg, ed);
    found[l.query] = 1;
  }
  for (std::size_t q = 0; q < n; ++q) {
    ev.keyframes_with_true_loop += has_true[q];
    ev.keyframes_with_loop_found += has_true[q] && found[q];
  }
  if (nees_count > 0) {
    ev.nees_mean /= static_cast<double>(nees_count);
    ev.nees_within_95 = double(nees_inside) / double(nees_count);
  }
  ev.recall =
      ev.keyframes_with_true_loop ? double(ev.keyframes_with_loop_found) / ev.keyframes_with_true_loop : 0;
  return ev;
}

std::string refusedRightText(const LoopEvaluation& evaluation) {
  std::string text;
  for (const auto& [reason, count] : evaluation.refused_right)
    text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + reason;
  return text.empty() ? "none" : text;
}

}  // namespace radarslam
