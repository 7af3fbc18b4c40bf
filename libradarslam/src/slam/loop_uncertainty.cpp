#include "loop_uncertainty.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

#include "graph_optimiser.h"
#include "radarslam/core/se2_covariance.h"

namespace radarslam::slam_detail {

Eigen::Matrix3d loopInformation(const Eigen::Matrix3d& verifier_information, const LoopClosingParams& p) {
  const double sxy = p.loop_sigma_xy_m, sphi = p.loop_sigma_phi_deg * M_PI / 180;
  const Eigen::Vector3d floor2(sxy * sxy, sxy * sxy, sphi * sphi);
  if (!p.loop_information_estimated) return floor2.cwiseInverse().asDiagonal();
  // A direction the alignment does not constrain gets a huge (not infinite) variance: 1e-9 of
  // regularisation is a 30 km sigma, far beyond any drift.
  const Eigen::Matrix3d alignment_cov = (verifier_information + 1e-9 * Eigen::Matrix3d::Identity()).inverse();
  Eigen::Matrix3d cov = alignment_cov;
  cov.diagonal() += floor2;
  return cov.inverse();
}

Eigen::Matrix3d slideLoopInformation(const Eigen::Matrix3d& information, const Eigen::Vector2d& along) {
  Eigen::Matrix3d cov = (information + 1e-9 * Eigen::Matrix3d::Identity()).inverse();
  cov.topLeftCorner<2, 2>() += 1e9 * along * along.transpose();
  const Eigen::Matrix3d out = cov.inverse();
  return 0.5 * (out + out.transpose());
}

bool uniqueWithinGate(const LoopVerification& v,
                      const std::function<bool(const TPose2D& relative)>& within_gate) {
  if (v.accepted || !v.ambiguous_only) return false;
  return std::none_of(v.rivals.begin(), v.rivals.end(), [&](const mrpt::math::TPose2D& r) {
    return within_gate(compose(v.relative_pose, TPose2D(r.x, r.y, r.phi)));
  });
}

namespace {
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }
}  // namespace

ChainCovariance::ChainCovariance(const SlamState& state, std::uint64_t first, std::uint64_t query,
                                 const OdometryEdgeParams& params)
    : first_(first) {
  prefix_.resize(query - first + 1);
  chain_.resize(query - first + 1, TPose2D(0, 0, 0));
  for (std::uint64_t k = first + 1; k <= query; ++k) {
    const SlamKeyframe& kf = state.keyframes[k];
    const TPose2D& e = kf.odom_edge;
    const std::size_t i = k - first;
    chain_[i] = compose(chain_[i - 1], e);
    const Eigen::Matrix3d edge_cov = odometryInformation(params, std::hypot(e.x, e.y), kf.lost).inverse();
    const double a = edge_cov(0, 0), b = edge_cov(2, 2);
    // The heading perturbation of edge i acts at keyframe k's position.
    const Eigen::Vector2d pp = perp(Eigen::Vector2d(chain_[i].x, chain_[i].y));
    Prefix& p = prefix_[i];
    p = prefix_[i - 1];
    p.a += a;
    p.b += b;
    p.bp += b * pp;
    p.bpp += b * pp * pp.transpose();
    p.session_starts += kf.session_start;
  }
}

Eigen::Matrix3d ChainCovariance::relativeTo(std::uint64_t m) const {
  const Prefix& hi = prefix_.back();
  const Prefix& lo = prefix_.at(m - first_);
  if (hi.session_starts != lo.session_starts)
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()).asDiagonal();
  const double a = hi.a - lo.a, b = hi.b - lo.b;
  const Eigen::Vector2d bp = hi.bp - lo.bp;
  const Eigen::Matrix2d bpp = hi.bpp - lo.bpp;
  const Eigen::Vector2d pq = perp(Eigen::Vector2d(chain_.back().x, chain_.back().y));
  // sum b_i (pq - pp_i)(pq - pp_i)^T and sum b_i (pq - pp_i), in first's frame.
  const Eigen::Matrix2d buu = b * pq * pq.transpose() - pq * bp.transpose() - bp * pq.transpose() + bpp;
  const Eigen::Vector2d bu = b * pq - bp;
  Eigen::Matrix3d cov;
  cov.topLeftCorner<2, 2>() = a * Eigen::Matrix2d::Identity() + buu;
  cov.topRightCorner<2, 1>() = bu;
  cov.bottomLeftCorner<1, 2>() = bu.transpose();
  cov(2, 2) = b;
  // Into m's frame.
  const double phi = chain_.at(m - first_).phi, c = std::cos(phi), s = std::sin(phi);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R.topLeftCorner<2, 2>() << c, -s, s, c;
  return R.transpose() * cov * R;
}

void DriftScaleEstimator::add(double unit_mahalanobis2) {
  if (!std::isfinite(unit_mahalanobis2)) return;
  samples_.push_back(unit_mahalanobis2);
  if (samples_.size() < min_samples_) return;
  std::vector<double> s = samples_;
  auto mid = s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2);
  std::nth_element(s.begin(), mid, s.end());
  constexpr double kChi2Median3 = 2.366;  // median of chi^2 with 3 degrees of freedom
  scale_ = std::max(1.0, *mid / kChi2Median3);
}

double correctionMahalanobis2(const TPose2D& loop_relative, const TPose2D& estimated_relative,
                              const Eigen::Matrix3d& chain_covariance,
                              const Eigen::Matrix3d& loop_information) {
  const Eigen::Vector3d d(estimated_relative.x - loop_relative.x, estimated_relative.y - loop_relative.y,
                          std::remainder(estimated_relative.phi - loop_relative.phi, 2 * M_PI));
  if (!chain_covariance.allFinite()) return 0;  // across a session start: nothing to test against
  // The loop's covariance is in the query's frame (the edge's error); d is in the match's.
  const Eigen::Matrix3d cov =
      chain_covariance + rotateCovariance(loop_information.inverse(), loop_relative.phi);
  return d.dot(cov.inverse() * d);
}

double graphPathLength(const SlamState& state, std::uint64_t from, std::uint64_t to) {
  const std::size_t n = state.keyframes.size();
  if (from >= n || to >= n) return std::numeric_limits<double>::infinity();
  // Loop edges by keyframe (built per call: called only for loops refused as ambiguous).
  std::vector<std::vector<std::uint64_t>> loops(n);
  for (const AcceptedLoop& l : state.loops)
    if (l.active && l.from < n && l.to < n) {
      loops[l.from].push_back(l.to);
      loops[l.to].push_back(l.from);
    }
  auto edgeLength = [&](std::size_t k) {  // odometry edge k - 1 -> k
    const TPose2D& e = state.keyframes[k].odom_edge;
    return std::hypot(e.x, e.y);
  };
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, std::uint64_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[from] = 0;
  open.emplace(0.0, from);
  while (!open.empty()) {
    const double d = open.top().first;  // (not a structured binding: lambdas capture it below)
    const std::uint64_t k = open.top().second;
    open.pop();
    if (k == to) return d;
    if (d > dist[k]) continue;
    auto relax = [&](std::uint64_t j, double length) {
      if (d + length < dist[j]) {
        dist[j] = d + length;
        open.emplace(dist[j], j);
      }
    };
    if (k > 0 && !state.keyframes[k].session_start) relax(k - 1, edgeLength(k));
    if (k + 1 < n && !state.keyframes[k + 1].session_start) relax(k + 1, edgeLength(k + 1));
    for (const std::uint64_t j : loops[k]) relax(j, 0.0);
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace radarslam::slam_detail
