#pragma once
// How uncertain a loop is, and how far odometry can have drifted (issue 13, item 6): loop and
// odometry information from estimated uncertainty, and the drift gate from the uncertainty
// accumulated along the keyframe chain, not from constants.
#include <Eigen/Core>

#include <functional>
#include <vector>

#include "radarslam/loop/loop_verifier.h"
#include "radarslam/slam/slam_params.h"
#include "slam_state.h"

namespace radarslam::slam_detail {

/// The information of a loop edge. Estimated: the verifier's alignment covariance (inverse of its
/// information; large where the place is degenerate) plus the model error that alignment cannot
/// see (a revisit views the place from elsewhere: other speckle, other peaks), diag(loop_sigma^2).
/// Otherwise diag(1 / loop_sigma^2).
Eigen::Matrix3d loopInformation(const Eigen::Matrix3d& verifier_information, const LoopClosingParams& params);

/// The information of a partial loop (LoopClosingParams::accept_slide_loops): `information` with
/// the direction `along` (unit, in the query's frame: that of the edge's error) made unconstrained
/// (variance 1e9 m^2 added along it, loopInformation's convention).
Eigen::Matrix3d slideLoopInformation(const Eigen::Matrix3d& information, const Eigen::Vector2d& along);

/// Whether a loop the verifier refused for its ambiguity alone (LoopVerification::ambiguous_only) is
/// unique among the relative poses the drift gate admits: every rival, as a relative pose
/// (the verified relative pose composed with the rival's offset), fails `within_gate`
/// (LoopClosingParams::ambiguity_within_drift_bound).
bool uniqueWithinGate(const LoopVerification& verification,
                      const std::function<bool(const TPose2D& relative)>& within_gate);

/// The length (metres of odometry) of the shortest path between keyframes `from` and `to` through
/// the graph: odometry edges cost their length, active accepted loops nothing (a loop ties the
/// two places together far more tightly than metres of odometry). Infinite when no path joins
/// them (another session not yet anchored). The drift a pose can have accumulated relative to
/// another is that of this path, not of the distance driven between them once loops exist.
double graphPathLength(const SlamState& state, std::uint64_t from, std::uint64_t to);

/// The covariance of keyframe `query`'s pose in an earlier keyframe m's frame when only the
/// odometry edges between them are known: first-order propagation of the edges' covariances
/// (odometryInformation, isotropic in x, y) through the chain of compositions. A heading error at
/// edge i swings everything after it about keyframe i, so
///   Sigma = sum_i [ a_i I + b_i u_i u_i^T , b_i u_i ; b_i u_i^T , b_i ],  u_i = perp(p_query - p_i)
/// (a_i, b_i: the edge's xy and heading variances) - built once per query from prefix sums, then
/// O(1) per candidate. A session start between m and the query makes the relative pose unknown
/// (+inf on the diagonal).
class ChainCovariance {
 public:
  /// The chain [first, query] of state's keyframes (call with the state locked).
  ChainCovariance(const SlamState& state, std::uint64_t first, std::uint64_t query,
                  const OdometryEdgeParams& params);
  /// Covariance (x, y, phi) of the query in keyframe m's frame, first <= m < query.
  Eigen::Matrix3d relativeTo(std::uint64_t m) const;

 private:
  struct Prefix {
    double a = 0, b = 0;
    Eigen::Vector2d bp = Eigen::Vector2d::Zero();
    Eigen::Matrix2d bpp = Eigen::Matrix2d::Zero();
    std::uint64_t session_starts = 0;
  };
  std::uint64_t first_ = 0;
  std::vector<Prefix> prefix_;  ///< sums over edges (first, first + k]
  std::vector<TPose2D> chain_;  ///< keyframe first + k in first's frame, by odometry alone
};

/// How much more the odometry drifts than its edge covariances say, from the verified loops
/// themselves (the way KISS-ICP sets its correspondence bound from its model's running error): a
/// loop's squared Mahalanobis correction under the unit chain covariance is, for a consistent model,
/// chi^2(3)-distributed, so the scale is median / median(chi^2(3)) = median / 2.366. The median
/// keeps it robust to the false loops among the verified ones; at least `min_samples` loops before
/// it moves; never below 1 (the parameters are the prior).
class DriftScaleEstimator {
 public:
  explicit DriftScaleEstimator(std::size_t min_samples = 5) : min_samples_(min_samples) {}
  void add(double unit_mahalanobis2);
  double scale() const { return scale_; }

 private:
  std::size_t min_samples_;
  std::vector<double> samples_;
  double scale_ = 1.0;
};

/// The drift gate: the squared Mahalanobis distance between the loop's relative pose and the
/// current estimate's (both: the query in the match keyframe's frame) under chain + loop
/// covariance (the loop's, given in the query's frame as the edge's error is, turned into the
/// match's frame). Compared with chi2(3).
double correctionMahalanobis2(const TPose2D& loop_relative, const TPose2D& estimated_relative,
                              const Eigen::Matrix3d& chain_covariance,
                              const Eigen::Matrix3d& loop_information);

}  // namespace radarslam::slam_detail
