// pose_refiner.h with the motion model as a prior: along a direction the matches leave free (a
// straight wall matched point to line) the prior decides; where the matches constrain the pose, a
// prior off by decimetres moves the estimate by less than a millimetre, and one the data contradicts
// beyond the chi^2 gate is not applied; a prior that is not positive definite is ignored.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "radarslam/frontend/pose_refiner.h"

namespace radarslam {
namespace {

/// Matches on a straight wall along x at y = 10 and -12 (a corridor), each known only across the
/// wall (point to line), rendered with the true motion plus a deterministic across-wall jitter;
/// the along-wall position of each spot moves with the sensor (it is where the wall faces it).
void corridor(const mrpt::math::TPose2D& truth, Correspondences& matches,
              std::vector<Eigen::Matrix2d>& shapes) {
  for (int i = 0; i < 60; ++i) {
    Correspondence m;
    m.cur = {-30.0 + i, i % 2 ? 10.0 : -12.0};
    const auto r = truth.composePoint({m.cur.x(), m.cur.y()});
    m.ref = {m.cur.x() + 0.3 * std::sin(i), r.y + 0.02 * std::cos(3.0 * i)};
    matches.push_back(m);
    shapes.push_back(Eigen::Vector2d(0, 1).asDiagonal());
  }
}

TEST(PoseRefinerPrior, AlongACorridorThePriorDecidesTheFreeDirection) {
  const mrpt::math::TPose2D truth(3.75, 0.05, 0.0);
  Correspondences matches;
  std::vector<Eigen::Matrix2d> shapes;
  corridor(truth, matches, shapes);
  RefineParams p;
  p.iterations = 30;
  // Without a prior the along-wall translation is whatever the start was (nothing constrains it).
  const RefineResult free = refinePose(matches, {1.0, 0, 0}, p, shapes);
  EXPECT_NEAR(free.pose.x, 1.0, 1e-6) << "the corridor leaves x free";
  // The constant-velocity prediction 3.6 m ahead, 0.2 m sigma: x comes from it, y from the walls.
  PosePrior prior{{3.6, 0.0, 0.0}, Eigen::Vector3d(0.04, 0.04, 1e-4).asDiagonal()};
  const RefineResult with = refinePose(matches, {1.0, 0, 0}, p, shapes, &prior);
  EXPECT_NEAR(with.pose.x, 3.6, 1e-3);
  EXPECT_NEAR(with.pose.y, truth.y, 0.01) << "across the walls the matches decide";
  EXPECT_NEAR(with.pose.phi, 0.0, 1e-3);
  EXPECT_TRUE(with.prior_applied) << "the walls cannot contradict it along themselves";
  // A prior that is not positive definite is ignored: the matches' estimate, bit for bit.
  PosePrior zero{{3.6, 0.0, 0.0}, Eigen::Matrix3d::Zero()};
  const RefineResult ignored = refinePose(matches, {1.0, 0, 0}, p, shapes, &zero);
  EXPECT_EQ(ignored.pose.x, free.pose.x);
  EXPECT_EQ(ignored.pose.y, free.pose.y);
  EXPECT_EQ(ignored.pose.phi, free.pose.phi);
}

TEST(PoseRefinerPrior, WellConstrainedMatchesOutweighAWrongPrior) {
  const mrpt::math::TPose2D truth(2.0, 0.1, 0.01);
  Correspondences matches;
  for (int i = 0; i < 300; ++i) {  // compact targets all round, 5 cm jitter
    Correspondence m;
    const double a = 0.021 * i, r = 10.0 + 0.25 * i;
    m.cur = {r * std::cos(a), r * std::sin(a)};
    const auto q = truth.composePoint({m.cur.x(), m.cur.y()});
    m.ref = {q.x + 0.05 * std::sin(7.0 * i), q.y + 0.05 * std::cos(5.0 * i)};
    matches.push_back(m);
  }
  RefineParams p;
  p.iterations = 30;
  const RefineResult data_only = refinePose(matches, {0, 0, 0}, p);
  // The prediction 0.15 m and 0.2 deg off, with the sigma the prediction error typically has:
  // within the innovation gate (chi^2 about 5), weighed, and outweighed.
  PosePrior prior{{2.15, -0.05, 0.01 + 0.2 * M_PI / 180}, Eigen::Vector3d(0.01, 0.01, 3e-5).asDiagonal()};
  const RefineResult with = refinePose(matches, {0, 0, 0}, p, {}, &prior);
  EXPECT_TRUE(with.prior_applied) << "chi2 " << with.prior_chi2;
  EXPECT_LT(std::hypot(with.pose.x - data_only.pose.x, with.pose.y - data_only.pose.y), 1e-3);
  EXPECT_LT(std::abs(with.pose.phi - data_only.pose.phi), 1e-4);
  EXPECT_GT(std::hypot(with.pose.x - data_only.pose.x, with.pose.y - data_only.pose.y), 0.0)
      << "the prior is weighed at all";
  // 0.5 m off: the data's estimate and the prediction disagree beyond chi^2(3) 99 %: the motion
  // left the model, the prior is not applied and the data's estimate stands unchanged.
  PosePrior far{{2.5, 0.1, 0.01}, Eigen::Vector3d(0.01, 0.01, 3e-5).asDiagonal()};
  const RefineResult gated = refinePose(matches, {0, 0, 0}, p, {}, &far);
  EXPECT_FALSE(gated.prior_applied);
  EXPECT_GT(gated.prior_chi2, p.motion_prior_chi2);
  EXPECT_EQ(gated.pose.x, data_only.pose.x);
  EXPECT_EQ(gated.pose.y, data_only.pose.y);
  EXPECT_EQ(gated.pose.phi, data_only.pose.phi);
}

}  // namespace
}  // namespace radarslam
