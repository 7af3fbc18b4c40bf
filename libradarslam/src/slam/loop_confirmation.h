#pragma once
// Ambiguous loops confirmed by the next keyframes (ours; issue 13, item 6). Along a featureless
// wall, or a street that looks alike further on, the verifier refuses almost every candidate as an
// ambiguous place (loop/loop_verifier.h: a distant alignment scores almost as well), so a street
// driven twice stays two streets in the map. Of those refusals whose best alignment passed every
// other test (LoopVerification::ambiguous_only), the right ones agree with each other from one
// keyframe to the next: each implies where its query keyframe really is, and consecutive queries,
// a few metres apart by odometry, must be placed consistently. A wrong best alignment (a slide
// along the wall, the other side of the road) lands somewhere else at every keyframe. So, as
// relocalisation needs consecutive agreeing fixes, an ambiguous loop enters the graph once the
// best alignments of `keyframes_needed` queries, each within `max_gap` keyframes of the previous
// one, agree pairwise along the chain: the query placed by loop a, moved by the odometry from a's
// query to b's, against where loop b places it, as a chi^2(3) test under both loops' covariances
// (the odometry over a few metres is far more certain than a loop: its covariance is left out).
// Later loops that agree with a confirmed chain enter at once. Unless a rival chain exists: two or
// more of the queries within the window agreeing on another placement (a street of look-alike
// blocks fits consistently at several places, which no single keyframe and no chain can tell
// apart), or a loop the verifier found unique that places them elsewhere; then nothing is
// confirmed until the rival has left the window. A unique loop that contradicts loops confirmed
// within the window withdraws them (addUnique).
#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "slam_state.h"

namespace radarslam::slam_detail {

/// A loop refused as ambiguous only, waiting for the next keyframes to confirm it.
struct PendingLoop {
  std::uint64_t query = 0, match = 0;  ///< keyframe ids (match older)
  TPose2D relative;                    ///< query in match's frame (the verifier's best alignment)
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  ///< of relative, full rank
  std::size_t record = 0;                                     ///< the caller's record of it
  /// false: a placement the caller's prior excludes (beyond the drift bound). It never enters the
  /// graph, but it still counts as a rival when two or more queries agree on it.
  bool eligible = true;
};

/// The chi^2 of loop b's placement of its query against loop a's moved along the odometry
/// (`pose` gives a keyframe's current estimate; a.query < b.query).
double loopDisagreementChi2(const PendingLoop& a, const PendingLoop& b,
                            const std::function<TPose2D(std::uint64_t)>& pose);

class LoopConfirmation {
 public:
  /// keyframes_needed >= 2, max_gap >= 1, chi2 > 0 (the pose graph's loop bound).
  LoopConfirmation(int keyframes_needed, std::uint64_t max_gap, double chi2);

  /// Adds `loop` (queries arrive in non-decreasing order) and returns the pending loops it
  /// confirms, itself included: those of a chain that now reaches keyframes_needed queries, or
  /// `loop` alone when it extends an already confirmed chain; nothing while a rival chain is in
  /// the window. Eligible and ineligible loops form separate chains; only eligible ones are
  /// returned, each once.
  std::vector<PendingLoop> add(const PendingLoop& loop, const std::function<TPose2D(std::uint64_t)>& pose);

  /// Adds a loop the verifier found unique (already in the graph). It confirms at once an ambiguous
  /// loop that agrees with it, and is a rival of any that does not. Returns the records of loops
  /// confirmed earlier within the window that it contradicts: a unique place outweighs places that
  /// looked alike elsewhere, so the caller withdraws them from the graph.
  std::vector<std::size_t> addUnique(const PendingLoop& loop,
                                     const std::function<TPose2D(std::uint64_t)>& pose);

  std::size_t pending() const { return entries_.size(); }
  /// How often a chain long enough was held back by a rival chain.
  std::size_t rivalled() const { return rivalled_; }

 private:
  struct Entry {
    PendingLoop loop;
    int chain = 1;  ///< distinct queries in the longest agreeing chain ending here
    /// That chain's loops not yet returned (empty once the chain is confirmed).
    std::vector<PendingLoop> unconfirmed;
    bool unique = false;  ///< from addUnique
  };
  void prune(std::uint64_t query);
  bool returned(std::size_t record) const;
  int needed_;
  std::uint64_t max_gap_;
  double chi2_;
  std::vector<Entry> entries_;         ///< loops whose query is within max_gap of the newest
  std::vector<std::size_t> returned_;  ///< records already returned (sorted)
  std::size_t rivalled_ = 0;
};

}  // namespace radarslam::slam_detail
