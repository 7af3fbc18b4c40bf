// Ambiguous loops confirmed by the next keyframes; see loop_confirmation.h.
#include "loop_confirmation.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "radarslam/core/se2_covariance.h"

namespace radarslam::slam_detail {

double loopDisagreementChi2(const PendingLoop& a, const PendingLoop& b,
                            const std::function<TPose2D(std::uint64_t)>& pose) {
  const TPose2D placed_a = compose(pose(a.match), a.relative);  // a's query where loop a puts it
  const TPose2D placed_b = compose(pose(b.match), b.relative);
  const TPose2D odometry = between(pose(a.query), pose(b.query));
  const TPose2D predicted_b = compose(placed_a, odometry);
  // Loop a's covariance (its error is in a's query frame) carried along the odometry into the
  // predicted pose's frame, plus loop b's own (in b's query frame).
  const Eigen::FullPivLU<Eigen::Matrix3d> lu_a(a.information), lu_b(b.information);
  if (!lu_a.isInvertible() || !lu_b.isInvertible()) return std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d cov_a_map = rotateCovariance(lu_a.inverse(), placed_a.phi);
  const Eigen::Matrix3d cov_pred_map =
      composeCovariance(placed_a, cov_a_map, odometry, Eigen::Matrix3d::Zero());
  const Eigen::Matrix3d cov = rotateCovariance(cov_pred_map, -predicted_b.phi) + lu_b.inverse();
  const TPose2D e = between(predicted_b, placed_b);
  const Eigen::Vector3d r(e.x, e.y, e.phi);
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(0.5 * (cov + cov.transpose()));
  if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return r.dot(ldlt.solve(r));
}

LoopConfirmation::LoopConfirmation(int keyframes_needed, std::uint64_t max_gap, double chi2)
    : needed_(keyframes_needed), max_gap_(max_gap), chi2_(chi2) {
  if (keyframes_needed < 2 || max_gap < 1 || !(chi2 > 0))
    throw std::invalid_argument("LoopConfirmation: needs keyframes_needed >= 2, max_gap >= 1, chi2 > 0");
}

void LoopConfirmation::prune(std::uint64_t query) {
  // A chain of `needed_` queries spans at most span keyframes: older loops can neither extend one
  // nor compete with one.
  const std::uint64_t span = max_gap_ * static_cast<std::uint64_t>(needed_);
  std::erase_if(entries_, [&](const Entry& e) { return e.loop.query + span < query; });
}

bool LoopConfirmation::returned(std::size_t record) const {
  return std::binary_search(returned_.begin(), returned_.end(), record);
}

std::vector<std::size_t> LoopConfirmation::addUnique(const PendingLoop& loop,
                                                     const std::function<TPose2D(std::uint64_t)>& pose) {
  prune(loop.query);
  std::vector<std::size_t> withdrawn;
  std::erase_if(entries_, [&](const Entry& e) {
    const bool contradicted = !e.unique && e.loop.eligible && returned(e.loop.record) &&
                              loopDisagreementChi2(e.loop, loop, pose) > chi2_;
    if (contradicted) withdrawn.push_back(e.loop.record);
    return contradicted;
  });
  // As good as a confirmed chain: ambiguous loops that agree with it enter at once.
  Entry entry{loop, needed_, {}};
  entry.unique = true;
  entries_.push_back(std::move(entry));
  return withdrawn;
}

std::vector<PendingLoop> LoopConfirmation::add(const PendingLoop& loop,
                                               const std::function<TPose2D(std::uint64_t)>& pose) {
  prune(loop.query);
  Entry entry{loop, 1, {loop}};
  // The longest agreeing chain this loop extends (an earlier query within the gap).
  const Entry* best = nullptr;
  auto longer = [](const Entry& e, const Entry* than) {
    if (!than) return true;
    if (e.chain != than->chain) return e.chain > than->chain;
    return e.unconfirmed.empty() && !than->unconfirmed.empty();  // a confirmed chain first
  };
  for (const Entry& e : entries_)
    if (e.loop.eligible == loop.eligible &&
        (e.loop.query < loop.query || (e.unique && e.loop.query == loop.query)) &&
        e.loop.query + max_gap_ >= loop.query && longer(e, best) &&
        loopDisagreementChi2(e.loop, loop, pose) <= chi2_)
      best = &e;
  std::vector<PendingLoop> out;
  if (best) {
    entry.chain = best->chain + 1;
    entry.unconfirmed = best->unconfirmed;  // empty when best's chain is confirmed
    entry.unconfirmed.push_back(loop);
    if (loop.eligible && (best->unconfirmed.empty() || entry.chain >= needed_)) out = entry.unconfirmed;
  }
  // A rival chain: another placement that two or more of these queries agree on (a street of
  // look-alike blocks fits at several places, each consistently). Then the sequence is as
  // ambiguous as each place was: nothing is confirmed until the rival has left the window.
  if (!out.empty())
    for (const Entry& e : entries_)
      if (e.chain >= 2 && loopDisagreementChi2(e.loop, loop, pose) > chi2_) {
        out.clear();
        ++rivalled_;
        break;
      }
  if (!out.empty()) entry.unconfirmed.clear();
  // Each loop once, whichever chain confirmed it.
  std::erase_if(out, [&](const PendingLoop& l) { return returned(l.record); });
  for (const PendingLoop& l : out)
    returned_.insert(std::upper_bound(returned_.begin(), returned_.end(), l.record), l.record);
  entries_.push_back(std::move(entry));
  return out;
}

}  // namespace radarslam::slam_detail
