// Pose graph: a square loop with drifted odometry is corrected by one loop edge; a wrong loop
// edge is removed by the chi^2 check; bad edges are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "radarslam/backend/pose_graph.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {
namespace {

using mrpt::math::TPose2D;

TPose2D compose(const TPose2D& a, const TPose2D& b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, std::remainder(a.phi + b.phi, 2 * M_PI)};
}
TPose2D between(const TPose2D& a, const TPose2D& b) {  // b in the frame of a
  const double c = std::cos(a.phi), s = std::sin(a.phi), dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, std::remainder(b.phi - a.phi, 2 * M_PI)};
}

/// A 40 m x 40 m square driven with a node every 2 m (80 nodes, back to the start).
std::vector<TPose2D> squareTruth() {
  std::vector<TPose2D> t;
  TPose2D p{0, 0, 0};
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < 20; ++k) {
      t.push_back(p);
      p = compose(p, {2.0, 0, k == 19 ? M_PI / 2 : 0.0});
    }
  }
  t.push_back(p);  // node 80, at the start again
  return t;
}

Eigen::Matrix3d info(double sigma_xy, double sigma_phi) {
  return Eigen::Vector3d(1 / (sigma_xy * sigma_xy), 1 / (sigma_xy * sigma_xy), 1 / (sigma_phi * sigma_phi))
      .asDiagonal();
}

double maxError(const PoseGraph& g, const std::vector<TPose2D>& truth) {
  double e = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    e = std::max(e, std::hypot(g.pose(i).x - truth[i].x, g.pose(i).y - truth[i].y));
  return e;
}

/// Odometry with a yaw bias (0.4 deg per step) and noise, dead-reckoned as the initial estimate.
PoseGraph driftedSquare(const std::vector<TPose2D>& truth, const PoseGraphParams& params = {}) {
  PoseGraph g(params);
  std::mt19937 rng(3);
  std::normal_distribution<double> n_xy(0, 0.02), n_phi(0, 0.002);
  TPose2D est = truth[0];
  g.addNode(est);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    TPose2D z = between(truth[i - 1], truth[i]);
    z.x += n_xy(rng), z.y += n_xy(rng), z.phi += 0.007 + n_phi(rng);
    est = compose(est, z);
    g.addNode(est);
    g.addOdometryEdge(i - 1, i, z, info(0.05, 0.01));
  }
  return g;
}

TEST(PoseGraph, OneLoopEdgeCorrectsADriftedSquare) {
  const auto truth = squareTruth();
  PoseGraph g = driftedSquare(truth);
  const double before = maxError(g, truth);
  EXPECT_GT(before, 5.0);  // the drift is real
  g.addLoopEdge(0, truth.size() - 1, between(truth.front(), truth.back()), info(0.05, 0.005));
  const auto report = g.optimize();
  EXPECT_TRUE(report.rejected_edges.empty());
  EXPECT_LT(report.chi2_final, report.chi2_initial);
  EXPECT_LT(maxError(g, truth), 0.6) << "before " << before;
  // The loop closes: the last node is back at the first.
  EXPECT_LT(std::hypot(g.pose(truth.size() - 1).x, g.pose(truth.size() - 1).y), 0.1);
}

TEST(PoseGraph, WrongLoopEdgeIsRejectedAndTheMapSurvives) {
  const auto truth = squareTruth();
  PoseGraph g = driftedSquare(truth);
  const auto good =
      g.addLoopEdge(0, truth.size() - 1, between(truth.front(), truth.back()), info(0.05, 0.005));
  // A false loop: node 30 (middle of side 2) claimed to be where node 70 (side 4) is; they are
  // 40 m apart. Confident, as a verifier's output would be.
  const auto bad = g.addLoopEdge(30, 70, TPose2D{0.5, 0.2, M_PI}, info(0.05, 0.005));
  const auto report = g.optimize();
  ASSERT_EQ(report.rejected_edges.size(), 1u);
  EXPECT_EQ(report.rejected_edges[0], bad);
  EXPECT_FALSE(g.edges()[bad].active);
  EXPECT_TRUE(g.edges()[good].active);
  EXPECT_LT(maxError(g, truth), 0.6);
}

TEST(PoseGraph, WithoutTheRobustCheckAWrongLoopWrecksTheMap) {
  const auto truth = squareTruth();
  PoseGraphParams p;
  p.max_loop_rejections = 0;
  PoseGraph g = driftedSquare(truth, p);
  g.addLoopEdge(0, truth.size() - 1, between(truth.front(), truth.back()), info(0.05, 0.005));
  g.addLoopEdge(30, 70, TPose2D{0.5, 0.2, M_PI}, info(0.05, 0.005));
  g.optimize();
  EXPECT_GT(maxError(g, truth), 5.0);
}

TEST(PoseGraph, RefusesBadEdgesAndReadsParams) {
  PoseGraph g;
  g.addNode({0, 0, 0});
  g.addNode({1, 0, 0});
  EXPECT_THROW(g.addOdometryEdge(0, 2, {1, 0, 0}, info(0.1, 0.1)), std::out_of_range);
  EXPECT_THROW(g.addOdometryEdge(1, 1, {1, 0, 0}, info(0.1, 0.1)), std::invalid_argument);
  Eigen::Matrix3d not_pd = info(0.1, 0.1);
  not_pd(2, 2) = -1;
  EXPECT_THROW(g.addLoopEdge(0, 1, {1, 0, 0}, not_pd), std::invalid_argument);
  PoseGraphParams p;
  loadParams(YamlParams::fromText("loop_chi2_gate: 11.3\nmax_loop_rejections: 2\n"), p);
  EXPECT_DOUBLE_EQ(p.loop_chi2_gate, 11.3);
  EXPECT_EQ(p.max_loop_rejections, 2);
  EXPECT_THROW(loadParams(YamlParams::fromText("loop_chi2_gate: -1\n"), p), InputError);
}

}  // namespace
}  // namespace radarslam
