#include "radarslam/slam/local_bundle_adjustment.h"

#include <ceres/ceres.h>

#include <cmath>
#include <deque>
#include <memory>

#include "ba_observation_cost.h"
#include "radarslam/slam/slam_params.h"

namespace radarslam {
namespace {

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

  // The observation costs live in one deque (a few allocations instead of one per residual); the
  // problem owns only the few prior costs.
  std::deque<slam_detail::ObservationCost> observation_costs;  // not movable: no reallocation
  for (const auto& o : pb.observations)
    observation_costs.emplace_back(o.z, params.observation_sigma_m, o.information);
  std::vector<std::unique_ptr<ceres::CostFunction>> prior_costs;
  ceres::Problem::Options po;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::HuberLoss huber(params.huber_sigmas);
  for (std::size_t i = 0; i < pb.observations.size(); ++i) {
    const BAObservation& o = pb.observations[i];
    problem.AddResidualBlock(&observation_costs[i], &huber, x[o.keyframe].data(), p[o.point].data());
  }
  for (const auto& pr : pb.priors) {
    prior_costs.push_back(std::make_unique<ceres::AutoDiffCostFunction<RelativePoseCost, 3, 3, 3>>(
        new RelativePoseCost(pr.relative, params.prior_sigma_xy_m, params.prior_sigma_phi_rad)));
    problem.AddResidualBlock(prior_costs.back().get(), nullptr, x[pr.from].data(), x[pr.to].data());
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
    const Eigen::Vector2d e = zl - o.z;
    report.outliers += std::sqrt(e.dot(o.information * e)) > gate;
  }
  return report;
}

}  // namespace radarslam
