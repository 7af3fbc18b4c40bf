// SE(2) pose graph on MRPT's SPA Levenberg-Marquardt with a chi^2 loop-edge check (paper
// Sec. III-D); see backend/pose_graph.h. The only file that includes MRPT's graph headers.
#include "radarslam/backend/pose_graph.h"

#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/graphslam/levmarq.h>
#include <mrpt/poses/CPose2D.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, PoseGraphParams& params) {
  yaml.get("max_iterations", params.max_iterations);
  yaml.get("loop_chi2_gate", params.loop_chi2_gate);
  yaml.get("max_loop_rejections", params.max_loop_rejections);
  if (params.max_iterations < 1 || !(params.loop_chi2_gate > 0) || params.max_loop_rejections < 0)
    throw InputError(yaml.origin(),
                     "pose graph: max_iterations >= 1, loop_chi2_gate > 0, max_loop_rejections >= 0");
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

PoseGraphReport PoseGraph::optimize() {
  PoseGraphReport report;
  report.chi2_initial = totalChi2();
  const std::vector<mrpt::math::TPose2D> initial = poses_;
  for (int pass = 0;; ++pass) {
    mrpt::graphs::CNetworkOfPoses2DInf graph;
    graph.root = 0;
    for (std::size_t i = 0; i < initial.size(); ++i)
      graph.nodes[static_cast<mrpt::graphs::TNodeID>(i)] = mrpt::poses::CPose2D(initial[i]);
    for (const auto& e : edges_) {
      if (!e.active) continue;
      mrpt::poses::CPosePDFGaussianInf z;
      z.mean = mrpt::poses::CPose2D(e.relative);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) z.cov_inv(r, c) = e.information(r, c);
      graph.insertEdge(static_cast<mrpt::graphs::TNodeID>(e.from), static_cast<mrpt::graphs::TNodeID>(e.to),
                       z);
    }
    mrpt::graphslam::TResultInfoSpaLevMarq info{};
    mrpt::containers::yaml extra;
    extra["max_iterations"] = static_cast<uint64_t>(params_.max_iterations);
    // MRPT's LM can stop early from a poor initial estimate (measured: a 1000-node, 10-lap graph
    // stops at chi^2 1002; restarting from its result reaches 258). Restart until chi^2 settles.
    double chi2 = std::numeric_limits<double>::infinity();
    for (int restart = 0; restart < 5; ++restart) {
      mrpt::graphslam::optimize_graph_spa_levmarq(graph, info, nullptr, extra);
      report.iterations += info.num_iters;
      const double now = graph.chi2();
      const bool settled = !(now < chi2 * (1.0 - 1e-3));
      chi2 = now;
      if (settled) break;
    }
    for (std::size_t i = 0; i < poses_.size(); ++i)
      poses_[i] = graph.nodes.at(static_cast<mrpt::graphs::TNodeID>(i)).asTPose();

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
