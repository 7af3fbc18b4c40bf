#include "radarslam/loop/alignment_information.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace radarslam {

namespace {

/// The candidate point's structure: its unit normal if the neighbourhood is a line, else zero.
Eigen::Vector2d lineNormal(const PointIndex2D& index, std::uint32_t point,
                           const AlignmentInformationParams& p,
                           std::vector<std::pair<std::uint32_t, double>>& scratch) {
  const auto& pts = index.points();
  index.within(pts[point], p.normal_radius_m, scratch);
  if (scratch.size() < 3) return Eigen::Vector2d::Zero();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& [i, d2] : scratch) mean += pts[i];
  mean /= static_cast<double>(scratch.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& [i, d2] : scratch) {
    const Eigen::Vector2d d = pts[i] - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  const double small = std::max(es.eigenvalues()(0), 0.0), large = es.eigenvalues()(1);
  if (large <= 0 || large < p.linearity_ratio * small) return Eigen::Vector2d::Zero();
  return es.eigenvectors().col(0);  // the smallest eigenvalue's direction: across the line
}

std::int64_t cellOf(const Eigen::Vector2d& q, double cell) {
  const auto ix = static_cast<std::int64_t>(std::floor(q.x() / cell));
  const auto iy = static_cast<std::int64_t>(std::floor(q.y() / cell));
  return (ix << 32) ^ (iy & 0xffffffff);
}

}  // namespace

Eigen::Matrix3d alignmentInformation(std::span<const Eigen::Vector2d> aligned_query,
                                     const Eigen::Vector2d& centre, const PointIndex2D& candidate,
                                     double inlier_distance_m, const AlignmentInformationParams& p) {
  struct Inlier {
    Eigen::Matrix<double, 2, 3> J;  // rows: the constrained directions (second row zero for a line)
    double residual2 = 0;           // squared residual along them
    int dims = 2;
    std::int64_t cell = 0;
  };
  std::vector<Inlier> inliers;
  inliers.reserve(aligned_query.size());
  std::vector<std::pair<std::uint32_t, double>> scratch;
  const double gate2 = inlier_distance_m * inlier_distance_m;
  for (const Eigen::Vector2d& q : aligned_query) {
    const auto [d2, idx] = candidate.nearest(q);
    if (d2 >= gate2) continue;
    Eigen::Matrix<double, 2, 3> full;
    const Eigen::Vector2d rq = q - centre;
    full << 1, 0, -rq.y(), 0, 1, rq.x();
    Inlier in;
    in.cell = cellOf(q, p.correlation_length_m);
    const Eigen::Vector2d n = lineNormal(candidate, idx, p, scratch);
    if (n.squaredNorm() > 0) {
      in.J.row(0) = n.transpose() * full;
      in.J.row(1).setZero();
      const double r = n.dot(q - candidate.points()[idx]);
      in.residual2 = r * r;
      in.dims = 1;
    } else {
      in.J = full;
      in.residual2 = d2;
    }
    inliers.push_back(in);
  }
  if (inliers.empty()) return Eigen::Matrix3d::Zero();
  std::unordered_map<std::int64_t, int> per_cell;
  double sum_r2 = 0;
  int dims = 0;
  for (const auto& in : inliers) {
    ++per_cell[in.cell];
    sum_r2 += in.residual2;
    dims += in.dims;
  }
  const double sigma = std::max(std::sqrt(sum_r2 / dims), p.min_sigma_m);
  Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
  for (const auto& in : inliers) info += in.J.transpose() * in.J / static_cast<double>(per_cell[in.cell]);
  return info / (sigma * sigma);
}

}  // namespace radarslam
