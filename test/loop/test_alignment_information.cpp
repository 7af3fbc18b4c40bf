// The alignment information of loop/alignment_information.h: a featureless wall constrains the
// distance to it, not the position along it; a corner constrains everything; more independent
// structure means more information, more points in one correlation cell do not.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "radarslam/loop/alignment_information.h"

namespace radarslam {
namespace {

std::vector<Eigen::Vector2d> wall(double y, double x0, double x1, double step) {
  std::vector<Eigen::Vector2d> pts;
  for (double x = x0; x <= x1; x += step) pts.emplace_back(x, y);
  return pts;
}

/// The candidate cloud and a query that is the same points with a little noise.
std::vector<Eigen::Vector2d> jittered(const std::vector<Eigen::Vector2d>& pts, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, sigma);
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : pts) out.emplace_back(p.x() + n(rng), p.y() + n(rng));
  return out;
}

TEST(AlignmentInformation, AWallConstrainsOnlyItsNormal) {
  const auto cand = wall(10, -40, 40, 0.25);
  const PointIndex2D index(cand);
  const auto query = jittered(cand, 0.05, 1);
  const Eigen::Matrix3d info = alignmentInformation(query, Eigen::Vector2d::Zero(), index, 1.0);
  // Along the wall (x) nothing; across it (y) a lot.
  EXPECT_LT(info(0, 0), 1e-6 * info(1, 1));
  EXPECT_GT(info(1, 1), 100.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(info);
  EXPECT_LT(es.eigenvalues()(0), 1e-6 * es.eigenvalues()(2));  // rank-deficient
}

TEST(AlignmentInformation, TwoWallsConstrainEverything) {
  auto cand = wall(10, -40, 40, 0.25);
  for (double y = -30; y <= 30; y += 0.25) cand.emplace_back(25, y);
  const PointIndex2D index(cand);
  const Eigen::Matrix3d info =
      alignmentInformation(jittered(cand, 0.05, 2), Eigen::Vector2d::Zero(), index, 1.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(info);
  EXPECT_GT(es.eigenvalues()(0), 1.0);  // full rank
}

TEST(AlignmentInformation, DenserSamplingOfTheSameWallAddsNoInformation) {
  AlignmentInformationParams p;
  p.min_sigma_m = 0.05;
  const auto sparse = wall(10, -40, 40, 1.0), dense = wall(10, -40, 40, 0.1);
  const PointIndex2D si(sparse), di(dense);
  const double s = alignmentInformation(jittered(sparse, 0.0, 3), {0, 0}, si, 1.0, p)(1, 1);
  const double d = alignmentInformation(jittered(dense, 0.0, 3), {0, 0}, di, 1.0, p)(1, 1);
  EXPECT_NEAR(d / s, 1.0, 0.15);
}

TEST(AlignmentInformation, LargerResidualsMeanLessInformation) {
  const auto cand = wall(10, -40, 40, 0.25);
  const PointIndex2D index(cand);
  const double tight = alignmentInformation(jittered(cand, 0.05, 4), {0, 0}, index, 1.0)(1, 1);
  const double loose = alignmentInformation(jittered(cand, 0.2, 4), {0, 0}, index, 1.0)(1, 1);
  EXPECT_GT(tight, 4 * loose);
}

TEST(AlignmentInformation, NoInliersNoInformation) {
  const auto cand = wall(10, -40, 40, 0.25);
  const PointIndex2D index(cand);
  const auto far = wall(100, -40, 40, 0.25);
  EXPECT_TRUE(alignmentInformation(far, {0, 0}, index, 1.0).isZero());
}

}  // namespace
}  // namespace radarslam
