// slam/loop_uncertainty.h: the chain covariance from prefix sums equals step-by-step first-order
// propagation; lateral uncertainty on a straight drive grows like distance^3 (heading random walk);
// a session start makes it unknown; the chi2 drift gate passes what the covariance explains.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <random>

#include "graph_optimiser.h"
#include "loop_uncertainty.h"

namespace radarslam::slam_detail {
namespace {

void fillChain(SlamState& s, int n, double step_m, double turn_rad) {
  for (int i = 0; i < n; ++i) {
    SlamKeyframe kf;
    kf.id = static_cast<std::uint64_t>(i);
    kf.odom_edge = TPose2D(step_m, 0.1 * std::sin(i), turn_rad * std::cos(0.3 * i));
    s.keyframes.push_back(kf);
  }
}

Eigen::Matrix3d propagated(const SlamState& s, std::uint64_t from, std::uint64_t to,
                           const OdometryEdgeParams& p) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  TPose2D rel(0, 0, 0);
  for (std::uint64_t k = from + 1; k <= to; ++k) {
    const TPose2D& e = s.keyframes[k].odom_edge;
    const Eigen::Matrix3d ec = odometryInformation(p, std::hypot(e.x, e.y), false).inverse();
    const double c = std::cos(rel.phi), sn = std::sin(rel.phi);
    Eigen::Matrix3d Jr, Je;
    Jr << 1, 0, -sn * e.x - c * e.y, 0, 1, c * e.x - sn * e.y, 0, 0, 1;
    Je << c, -sn, 0, sn, c, 0, 0, 0, 1;
    cov = Jr * cov * Jr.transpose() + Je * ec * Je.transpose();
    rel = compose(rel, e);
  }
  return cov;
}

TEST(ChainCovariance, EqualsStepByStepPropagation) {
  const OdometryEdgeParams p;
  SlamState s;
  fillChain(s, 120, 2.0, 0.05);
  const ChainCovariance chain(s, 10, 119, p);
  for (const std::uint64_t m : {10u, 30u, 77u, 118u}) {
    const Eigen::Matrix3d expected = propagated(s, m, 119, p), got = chain.relativeTo(m);
    EXPECT_LT((expected - got).norm(), 1e-9 * (1 + expected.norm())) << "from " << m;
  }
}

TEST(ChainCovariance, LateralUncertaintyGrowsWithTheCubeOfDistance) {
  const OdometryEdgeParams p;
  SlamState s;
  for (int i = 0; i < 401; ++i) {
    SlamKeyframe kf;
    kf.odom_edge = TPose2D(2.0, 0, 0);
    s.keyframes.push_back(kf);
  }
  const ChainCovariance chain(s, 0, 400, p);
  const double near = chain.relativeTo(300)(1, 1), far = chain.relativeTo(200)(1, 1);  // 200 m vs 400 m
  EXPECT_NEAR(far / near, 8.0, 1.0);
}

TEST(GraphPathLength, AnAcceptedLoopIsAShortcutAndASessionStartACut) {
  SlamState s;
  fillChain(s, 100, 2.0, 0.0);  // odometry edges of ~2 m (2.0 forward, 0.1 sin(i) sideways)
  const double driven = graphPathLength(s, 10, 90);
  EXPECT_NEAR(driven, 160.0, 1.0);
  EXPECT_DOUBLE_EQ(graphPathLength(s, 90, 10), driven);
  // A loop 20 -> 85: 10 -> 20 -> 85 -> 90 is 30 m of odometry.
  AcceptedLoop loop;
  loop.from = 20;
  loop.to = 85;
  s.loops.push_back(loop);
  EXPECT_NEAR(graphPathLength(s, 10, 90), 30.0, 0.5);
  s.loops.back().active = false;  // removed by the graph's chi^2 test: no shortcut
  EXPECT_DOUBLE_EQ(graphPathLength(s, 10, 90), driven);
  s.keyframes[50].session_start = true;  // no odometry edge 49 -> 50
  EXPECT_TRUE(std::isinf(graphPathLength(s, 10, 90)));
  s.loops.back().active = true;
  EXPECT_NEAR(graphPathLength(s, 10, 90), 30.0, 0.5);
}

TEST(ChainCovariance, ASessionStartMakesTheRelativePoseUnknown) {
  const OdometryEdgeParams p;
  SlamState s;
  fillChain(s, 50, 2.0, 0.0);
  s.keyframes[20].session_start = true;
  const ChainCovariance chain(s, 0, 49, p);
  EXPECT_FALSE(chain.relativeTo(10).allFinite());
  EXPECT_TRUE(chain.relativeTo(30).allFinite());
}

TEST(DriftGate, PassesWhatTheCovarianceExplainsAndRejectsTheRest) {
  const Eigen::Matrix3d chain = Eigen::Vector3d(1.0, 4.0, 0.01).asDiagonal();
  const Eigen::Matrix3d loop_info = Eigen::Vector3d(1e4, 1e4, 1e6).asDiagonal();
  const TPose2D loop(10, 0, 0);
  EXPECT_LT(correctionMahalanobis2(loop, TPose2D(11, 2, 0.05), chain, loop_info), 16.27);
  EXPECT_GT(correctionMahalanobis2(loop, TPose2D(10, 12, 0), chain, loop_info), 16.27);
  EXPECT_GT(correctionMahalanobis2(loop, TPose2D(10, 0, 0.6), chain, loop_info), 16.27);
}

TEST(LoopInformation, EstimatedKeepsTheAlignmentsDegeneracyAndTheModelFloor) {
  LoopClosingParams p;
  p.loop_information_estimated = true;
  Eigen::Matrix3d wall = Eigen::Vector3d(0, 1e6, 1e8).asDiagonal();  // nothing along x
  const Eigen::Matrix3d info = loopInformation(wall, p);
  EXPECT_LT(info(0, 0), 1e-3);                                                // along the wall: unknown
  EXPECT_NEAR(info(1, 1), 1 / (p.loop_sigma_xy_m * p.loop_sigma_xy_m), 1.0);  // across: the floor
  p.loop_information_estimated = false;
  EXPECT_NEAR(loopInformation(wall, p)(0, 0), 1 / (p.loop_sigma_xy_m * p.loop_sigma_xy_m), 1e-9);
}

// The loop's covariance is given in the query's frame (the pose graph's edge error); the gate's
// difference is in the match's. A loop unknown along the query's x, at 90 degrees to the match:
// unknown along the match's y.
TEST(DriftGate, TurnsTheLoopCovarianceIntoTheMatchsFrame) {
  const Eigen::Matrix3d chain = Eigen::Vector3d(0.01, 0.01, 1e-4).asDiagonal();
  const Eigen::Matrix3d loop_info = Eigen::Vector3d(1e-6, 100, 1e4).asDiagonal();  // unknown along x
  const TPose2D loop(10, 0, M_PI / 2);
  EXPECT_LT(correctionMahalanobis2(loop, TPose2D(10, 30, M_PI / 2), chain, loop_info), 1.0);
  EXPECT_GT(correctionMahalanobis2(loop, TPose2D(13, 0, M_PI / 2), chain, loop_info), 100.0);
}

TEST(LoopInformation, APartialLoopConstrainsOnlyAcrossItsLine) {
  LoopClosingParams p;
  const Eigen::Matrix3d full = loopInformation(Eigen::Matrix3d::Zero(), p);
  const Eigen::Vector2d along(std::cos(0.3), std::sin(0.3)), across(-along.y(), along.x());
  const Eigen::Matrix3d info = slideLoopInformation(full, along);
  EXPECT_TRUE(info.isApprox(info.transpose()));
  const Eigen::Vector3d a(along.x(), along.y(), 0), c(across.x(), across.y(), 0), h(0, 0, 1);
  EXPECT_LT(a.dot(info * a), 1e-8);                                  // along the line: unconstrained
  EXPECT_NEAR(c.dot(info * c), c.dot(full * c), 1e-6 * full(0, 0));  // across: as the full loop
  EXPECT_NEAR(h.dot(info * h), h.dot(full * h), 1e-6 * full(2, 2));  // heading: as the full loop
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(info).eigenvalues().minCoeff(), 0.0);
}

// A loop refused only because the place also fits elsewhere is unique where the drift gate lets a
// loop be when every rival, as a relative pose (verified pose (+) rival offset), is outside the gate.
TEST(UniqueWithinGate, RivalsTheGateRefusesDoNotMakeAPlaceAmbiguous) {
  LoopVerification v;
  v.ambiguous_only = true;
  v.relative_pose = TPose2D(10, 0, M_PI / 2);  // the query 10 m ahead of the match, turned left
  v.rivals = {TPose2D(0, 30, 0)};              // 30 m to the query's left: (-20, 0) in the match's frame
  // A gate around the match's origin, 15 m: the rival (20 m away) is outside, the best (10 m) inside.
  auto near_origin = [](const TPose2D& rel) { return std::hypot(rel.x, rel.y) < 15; };
  EXPECT_TRUE(uniqueWithinGate(v, near_origin));
  // Composed the other way round (offset in the match's frame) the rival would be at (10, 30),
  // 31.6 m away; a gate that admits (-20, 0) but not (10, 30) tells the two apart.
  auto left_of_match = [](const TPose2D& rel) { return rel.x < -15 || std::hypot(rel.x, rel.y) < 15; };
  EXPECT_FALSE(uniqueWithinGate(v, left_of_match));
  // Not refused for the ambiguity alone, or accepted anyway: nothing to decide.
  v.ambiguous_only = false;
  EXPECT_FALSE(uniqueWithinGate(v, near_origin));
  v.ambiguous_only = true;
  v.accepted = true;
  EXPECT_FALSE(uniqueWithinGate(v, near_origin));
}

TEST(DriftScaleEstimator, RecoversHowMuchMoreTheOdometryDriftsAndIgnoresAFewFalseLoops) {
  // Corrections drawn from a model 9x more uncertain than the unit one: unit NIS = 9 chi2(3).
  std::mt19937 rng(5);
  std::chi_squared_distribution<double> chi2(3);
  DriftScaleEstimator est;
  for (int i = 0; i < 400; ++i) est.add(9 * chi2(rng));
  for (int i = 0; i < 40; ++i) est.add(1e6);  // false loops 10 % of the verified ones
  EXPECT_NEAR(est.scale(), 9 * 1.1, 9 * 0.25);
}

TEST(DriftScaleEstimator, NeverBelowThePriorAndNotBeforeEnoughLoops) {
  DriftScaleEstimator est(5);
  for (int i = 0; i < 4; ++i) est.add(1000);
  EXPECT_DOUBLE_EQ(est.scale(), 1.0);
  est.add(1000);
  EXPECT_GT(est.scale(), 100.0);
  DriftScaleEstimator good;
  for (int i = 0; i < 50; ++i) good.add(0.1);
  EXPECT_DOUBLE_EQ(good.scale(), 1.0);
}

}  // namespace
}  // namespace radarslam::slam_detail
