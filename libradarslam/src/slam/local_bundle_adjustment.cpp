#include "radarslam/slam/local_bundle_adjustment.h"

#include <ceres/ceres.h>

#include <cmath>

#include "radarslam/slam/slam_params.h"

namespace radarslam {
namespace {

/// r = (R(phi)^T (p - t) - z) / sigma, pose = (x, y, phi), point = (x, y).
struct ObservationCost {
  ObservationCost(const Eigen::Vector2d& z, double sigma) : z_(z), inv_sigma_(1.0 / sigma) {}
  template <typename T>
  bool operator()(const T* pose, const T* point, T* r) const {
    const T c = ceres::cos(pose[2]), s = ceres::sin(pose[2]);
    const T dx = point[0] - pose[0], dy = point[1] - pose[1];
    r[0] = (c * dx + s * dy - T(z_.x())) * T(inv_sigma_);
    r[1] = (-s * dx + c * dy - T(z_.y())) * T(inv_sigma_);
    return true;
  }
  Eigen::Vector2d z_;
  double inv_sigma_;
};

/// Relative-pose prior: (from^-1 (+) to) (-) measured, weighted per component.
struct RelativePoseCost {
  RelativePoseCost(const mrpt::math::TPose2D& m, double sxy, double sphi)
      : m_(m), wxy_(1 / sxy), wphi_(1 / sphi) {}
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    const T c = ceres::cos(a[2]), s = ceres::sin(a[2]);
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    const T rx = c * dx + s * dy, ry = -s * dx + c * dy;
    T dphi = b[2] - a[2] - T(m_.phi);
    dphi = ceres::atan2(ceres::sin(dphi), ceres::cos(dphi));
    r[0] = (rx - T(m_.x)) * T(wxy_);
    r[1] = (ry - T(m_.y)) * T(wxy_);
    r[2] = dphi * T(wphi_);
    return true;
  }
  mrpt::math::TPose2D m_;
  double wxy_, wphi_;
};

}  // namespace

BAReport solveLocalBundleAdjustment(BAProblem& pb, const LocalMappingParams& params) {
  BAReport report;
  if (pb.poses.empty()) return report;
  std::vector<std::array<double, 3>> x(pb.poses.size());
  for (std::size_t i = 0; i < pb.poses.size(); ++i) x[i] = {pb.poses[i].x, pb.poses[i].y, pb.poses[i].phi};
  std::vector<std::array<double, 2>> p(pb.points.size());
  for (std::size_t j = 0; j < pb.points.size(); ++j) p[j] = {pb.points[j].x(), pb.points[j].y()};

  ceres::Problem::Options po;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::HuberLoss huber(params.huber_sigmas);
  for (const auto& o : pb.observations) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<ObservationCost, 2, 3, 2>(
                                 new ObservationCost(o.z, params.observation_sigma_m)),
                             &huber, x[o.keyframe].data(), p[o.point].data());
  }
  for (const auto& pr : pb.priors) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RelativePoseCost, 3, 3, 3>(new RelativePoseCost(
                                 pr.relative, params.prior_sigma_xy_m, params.prior_sigma_phi_rad)),
                             nullptr, x[pr.from].data(), x[pr.to].data());
  }
  bool any_fixed = false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!problem.HasParameterBlock(x[i].data())) continue;
    if (i < pb.fixed.size() && pb.fixed[i]) {
      problem.SetParameterBlockConstant(x[i].data());
      any_fixed = true;
    }
  }
  if (!any_fixed && problem.HasParameterBlock(x[0].data())) problem.SetParameterBlockConstant(x[0].data());

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_SCHUR;
  options.max_num_iterations = params.max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  report.initial_cost = summary.initial_cost;
  report.final_cost = summary.final_cost;
  report.iterations = static_cast<int>(summary.iterations.size());
  report.converged = summary.termination_type == ceres::CONVERGENCE;
  if (summary.termination_type == ceres::FAILURE) return report;  // keep the input

  for (std::size_t i = 0; i < x.size(); ++i)
    pb.poses[i] = {x[i][0], x[i][1], std::remainder(x[i][2], 2 * M_PI)};
  for (std::size_t j = 0; j < p.size(); ++j) pb.points[j] = {p[j][0], p[j][1]};
  const double gate = params.huber_sigmas * params.observation_sigma_m;
  for (const auto& o : pb.observations) {
    const auto& q = pb.poses[o.keyframe];
    const double c = std::cos(q.phi), s = std::sin(q.phi);
    const Eigen::Vector2d d = pb.points[o.point] - Eigen::Vector2d(q.x, q.y);
    const Eigen::Vector2d zl(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    report.outliers += (zl - o.z).norm() > gate;
  }
  return report;
}

}  // namespace radarslam
