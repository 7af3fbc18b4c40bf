// SE(2) pose graph, Levenberg-Marquardt with sparse Cholesky (Ceres), with a chi^2 loop-edge check
// (paper Sec. III-D); see backend/pose_graph.h.
#include "radarslam/backend/pose_graph.h"

#include <ceres/ceres.h>
#include <mrpt/poses/CPose2D.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, PoseGraphParams& params) {
  yaml.get("max_iterations", params.max_iterations, Range::closed(1, 10000));
  yaml.get("loop_chi2_gate", params.loop_chi2_gate, Range::above(0, 1000000.0));
  yaml.get("max_loop_rejections", params.max_loop_rejections, Range::closed(0, 10000));
}

PoseGraph::PoseGraph(const PoseGraphParams& params) : params_(params) {}
PoseGraph::~PoseGraph() = default;

std::size_t PoseGraph::addNode(const mrpt::math::TPose2D& initial) {
  poses_.push_back(initial);
  return poses_.size() - 1;
}

std::size_t PoseGraph::addEdge(std::size_t from, std::size_t to, const mrpt::math::TPose2D& relative,
                               const Eigen::Matrix3d& information, bool is_loop) {
  if (from >= poses_.size() || to >= poses_.size())
    throw std::out_of_range("PoseGraph: edge to an unknown node");
  if (from == to) throw std::invalid_argument("PoseGraph: edge from a node to itself");
  if (!information.isApprox(information.transpose(), 1e-9) ||
      Eigen::LLT<Eigen::Matrix3d>(information).info() != Eigen::Success)
    throw std::invalid_argument("PoseGraph: information matrix is not symmetric positive definite");
  edges_.push_back({from, to, relative, information, is_loop, true});
  return edges_.size() - 1;
}

std::size_t PoseGraph::addOdometryEdge(std::size_t from, std::size_t to, const mrpt::math::TPose2D& relative,
                                       const Eigen::Matrix3d& information) {
  return addEdge(from, to, relative, information, false);
}

std::size_t PoseGraph::addLoopEdge(std::size_t from, std::size_t to, const mrpt::math::TPose2D& relative,
                                   const Eigen::Matrix3d& information) {
  return addEdge(from, to, relative, information, true);
}

double PoseGraph::edgeChi2(std::size_t i) const {
  const GraphEdge& e = edges_.at(i);
  const mrpt::poses::CPose2D a(poses_[e.from]), b(poses_[e.to]), z(e.relative);
  const mrpt::poses::CPose2D err = (-z) + ((-a) + b);  // z^-1 (+) (a^-1 (+) b)
  const Eigen::Vector3d r(err.x(), err.y(), mrpt::math::wrapToPi(err.phi()));
  return r.dot(e.information * r);
}

double PoseGraph::totalChi2() const {
  double s = 0;
  for (std::size_t i = 0; i < edges_.size(); ++i)
    if (edges_[i].active) s += edgeChi2(i);
  return s;
}

namespace {

// Edge residual of eq. (5)-style SE(2) constraints: r = z^-1 (+) (a^-1 (+) b) as (x, y, wrapped
// phi), whitened by the upper Cholesky factor of the information (r^T Omega r = |L^T r|^2).
struct EdgeCost {
  EdgeCost(const mrpt::math::TPose2D& z, const Eigen::Matrix3d& information)
      : zx(z.x), zy(z.y), zphi(z.phi), sqrt_info(information.llt().matrixU()) {}
  template <typename T>
  bool operator()(const T* a, const T* b, T* out) const {
    using std::cos, std::sin;
    // a^-1 (+) b
    const T ca = cos(a[2]), sa = sin(a[2]);
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    const T rx = ca * dx + sa * dy, ry = -sa * dx + ca * dy, rphi = b[2] - a[2];
    // z^-1 (+) that
    const T cz = T(std::cos(zphi)), sz = T(std::sin(zphi));
    const T ex = cz * (rx - T(zx)) + sz * (ry - T(zy));
    const T ey = -sz * (rx - T(zx)) + cz * (ry - T(zy));
    T ephi = rphi - T(zphi);
    ephi -= T(2 * M_PI) * ceres::floor((ephi + T(M_PI)) / T(2 * M_PI));  // wrap to [-pi, pi)
    const Eigen::Matrix<T, 3, 1> e(ex, ey, ephi);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(out);
    r = sqrt_info.cast<T>() * e;
    return true;
  }
  double zx, zy, zphi;
  Eigen::Matrix3d sqrt_info;
};

}  // namespace

PoseGraphReport PoseGraph::optimize() {
  PoseGraphReport report;
  report.chi2_initial = totalChi2();
  const std::vector<mrpt::math::TPose2D> initial = poses_;
  for (int pass = 0;; ++pass) {
    std::vector<std::array<double, 3>> x(initial.size());
    for (std::size_t i = 0; i < initial.size(); ++i) x[i] = {initial[i].x, initial[i].y, initial[i].phi};
    ceres::Problem problem;
    for (const auto& e : edges_) {
      if (!e.active) continue;
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<EdgeCost, 3, 3, 3>(new EdgeCost(e.relative, e.information)),
          nullptr, x[e.from].data(), x[e.to].data());
    }
    if (!x.empty() && problem.HasParameterBlock(x[0].data())) problem.SetParameterBlockConstant(x[0].data());
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;  // sparse: linear in graph size
    options.max_num_iterations = params_.max_iterations;
    options.num_threads = 1;  // deterministic
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    report.iterations += summary.iterations.size();
    for (std::size_t i = 0; i < poses_.size(); ++i)
      poses_[i] = {x[i][0], x[i][1], mrpt::math::wrapToPi(x[i][2])};

    // Robust check: the worst loop edge beyond the gate goes, then re-optimise from scratch.
    std::size_t worst = edges_.size();
    double worst_chi2 = params_.loop_chi2_gate;
    for (std::size_t i = 0; i < edges_.size(); ++i) {
      if (!edges_[i].active || !edges_[i].is_loop) continue;
      const double c = edgeChi2(i);
      if (c > worst_chi2) worst_chi2 = c, worst = i;
    }
    if (worst == edges_.size() || pass >= params_.max_loop_rejections) break;
    edges_[worst].active = false;
    report.rejected_edges.push_back(worst);
  }
  report.chi2_final = totalChi2();
  return report;
}

}  // namespace radarslam
