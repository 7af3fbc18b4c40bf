// Consistency graph (eq. (3)), SVD pose and eq. (4) refinement on synthetic correspondences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "radarslam/frontend/consistency_graph.h"
#include "radarslam/frontend/pose_refiner.h"
#include "radarslam/frontend/svd_pose.h"

namespace radarslam {
namespace {

/// `inliers` points moved by T_ref_cur = truth (ref = T (+) cur), then `outliers` random pairs.
Correspondences makeMatches(const mrpt::math::TPose2D& truth, int inliers, int outliers, double noise,
                            unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-80, 80);
  std::normal_distribution<double> n(0, noise);
  Correspondences out;
  for (int i = 0; i < inliers + outliers; ++i) {
    Correspondence m;
    m.cur = {u(rng), u(rng)};
    const auto r = truth.composePoint({m.cur.x(), m.cur.y()});
    m.ref = i < inliers ? Eigen::Vector2d(r.x + n(rng), r.y + n(rng)) : Eigen::Vector2d(u(rng), u(rng));
    out.push_back(m);
  }
  return out;
}

TEST(ConsistencyGraph, InliersFormACliqueOutliersDoNot) {
  const mrpt::math::TPose2D truth(2.3, -0.4, 0.08);
  const auto matches = makeMatches(truth, 60, 40, 0.0, 1);
  const DenseGraph g = buildConsistencyGraph(matches, 0.5);
  for (int i = 0; i < 60; ++i)
    for (int j = i + 1; j < 60; ++j) ASSERT_TRUE(g.adjacent(i, j));
  const CliqueResult c = maximumClique(g);
  ASSERT_EQ(c.vertices.size(), 60u);
  for (int v : c.vertices) EXPECT_LT(v, 60);
}

TEST(ConsistencyGraph, PrintedDisplacementTestBreaksUnderRotation) {
  // Turning by 0.1 rad moves a point 80 m away 8 m but a point 5 m away 0.5 m: eq. (3) as
  // printed (displacement lengths) calls them inconsistent, the distance-preserving test does not.
  Correspondences m(2);
  const mrpt::math::TPose2D turn(0, 0, 0.1);
  m[0].cur = {80, 0};
  m[1].cur = {5, 0};
  for (auto& c : m) {
    const auto r = turn.composePoint({c.cur.x(), c.cur.y()});
    c.ref = {r.x, r.y};
  }
  EXPECT_TRUE(buildConsistencyGraph(m, 0.5, ConsistencyTest::PairwiseDistance).adjacent(0, 1));
  EXPECT_FALSE(buildConsistencyGraph(m, 0.5, ConsistencyTest::DisplacementLength).adjacent(0, 1));
}

// mrpt::tfest stores matched points as float: "exact" means to float precision at 80 m.
constexpr double kFloatTolM = 2e-5, kFloatTolRad = 1e-6;

TEST(SvdPose, ExactOnNoiseFreeCorrespondences) {
  const mrpt::math::TPose2D truth(-1.7, 3.2, -0.3);
  const auto pose = fitPoseSvd(makeMatches(truth, 20, 0, 0.0, 2));
  ASSERT_TRUE(pose);
  EXPECT_NEAR(pose->x, truth.x, kFloatTolM);
  EXPECT_NEAR(pose->y, truth.y, kFloatTolM);
  EXPECT_NEAR(pose->phi, truth.phi, kFloatTolRad);
  EXPECT_FALSE(fitPoseSvd(Correspondences(1)));
}

TEST(SvdPose, ExactAfterCliqueRemovesOutliers) {
  const mrpt::math::TPose2D truth(2.0, 0.1, 0.02);
  const auto matches = makeMatches(truth, 50, 150, 0.0, 3);  // 75 % outliers
  const CliqueResult c = maximumClique(buildConsistencyGraph(matches, 0.3));
  Correspondences in;
  for (int v : c.vertices) in.push_back(matches[v]);
  const auto pose = fitPoseSvd(in);
  ASSERT_TRUE(pose);
  EXPECT_NEAR(pose->x, truth.x, kFloatTolM);
  EXPECT_NEAR(pose->y, truth.y, kFloatTolM);
  EXPECT_NEAR(pose->phi, truth.phi, kFloatTolRad);
  // Without outlier rejection the same fit is far off.
  const auto bad = fitPoseSvd(matches);
  EXPECT_GT(std::hypot(bad->x - truth.x, bad->y - truth.y), 0.5);
}

TEST(PoseRefiner, HuberRefinementResistsResidualOutliers) {
  const mrpt::math::TPose2D truth(1.5, -0.2, 0.015);
  auto matches = makeMatches(truth, 300, 0, 0.05, 4);
  for (int i = 0; i < 30; ++i) matches[i].ref += Eigen::Vector2d(0.8, -0.6);  // gross but gated-in errors
  const auto l2 = fitPoseSvd(matches);
  RefineParams p;
  p.huber_m = 0.1;
  const RefineResult r = refinePose(matches, *l2, p);
  const double err_l2 = std::hypot(l2->x - truth.x, l2->y - truth.y);
  const double err = std::hypot(r.pose.x - truth.x, r.pose.y - truth.y);
  EXPECT_LT(err, 0.02);
  EXPECT_LT(err, 0.5 * err_l2);
  EXPECT_NEAR(r.pose.phi, truth.phi, 3e-4);
}

TEST(PoseRefiner, ConvergesFromAPoorStart) {
  const mrpt::math::TPose2D truth(3.0, 1.0, 0.2);
  const auto matches = makeMatches(truth, 100, 0, 0.0, 5);
  RefineParams p;
  p.huber_m = 100;  // plain least squares (the paper's eq. (4))
  p.iterations = 20;
  const RefineResult r = refinePose(matches, {0, 0, 0}, p);
  EXPECT_NEAR(r.pose.x, truth.x, 1e-6);
  EXPECT_NEAR(r.pose.y, truth.y, 1e-6);
  EXPECT_NEAR(r.pose.phi, truth.phi, 1e-8);
  EXPECT_LT(r.rms_m, 1e-6);
}

}  // namespace
}  // namespace radarslam
