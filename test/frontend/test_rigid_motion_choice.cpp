// The second rigid motion (frontend/rigid_motion_choice.h): beside a featureless wall a vehicle in
// the next lane can be the largest rigid set; its motion must lose to the static world's when the
// constant-velocity prediction says so, and never win where the static world is the larger set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "radarslam/frontend/consistency_graph.h"
#include "radarslam/frontend/rigid_motion_choice.h"

namespace radarslam {
namespace {

constexpr double kDeltaC = 0.75;  // eq. (3) threshold of the shipped configs
constexpr int kMinInliers = 10;

/// n points in [x0, x1] x [y0, y1] (the current scan) matched to where `motion` puts them in the
/// keyframe (ref = motion (+) cur), with Gaussian noise.
void addRigidSet(Correspondences& out, const mrpt::math::TPose2D& motion, int n, double x0, double x1,
                 double y0, double y1, std::mt19937& rng) {
  std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1);
  std::normal_distribution<double> noise(0, 0.05);
  for (int i = 0; i < n; ++i) {
    Correspondence m;
    m.cur = {ux(rng), uy(rng)};
    const auto r = motion.composePoint({m.cur.x(), m.cur.y()});
    m.ref = {r.x + noise(rng), r.y + noise(rng)};
    m.cur_index = static_cast<int>(out.size());
    m.ref_index = m.cur_index;
    out.push_back(m);
  }
}

MotionPrediction prediction(const mrpt::math::TPose2D& predicted) {
  return {predicted, /*sigma_m=*/0.12, /*search_radius_m=*/1.1, /*keypoint_sigma_m=*/0.25};
}

/// The choice keeps the maximum clique `first`.
void expectFirstKept(const Correspondences& matches, const DenseGraph& g, const CliqueResult& first,
                     const MotionPrediction& p) {
  const RigidMotionChoice choice = chooseRigidMotion(matches, g, first.vertices, p, kMinInliers, 0);
  EXPECT_FALSE(choice.second);
  EXPECT_EQ(choice.vertices, first.vertices);
}

bool allBelow(const std::vector<int>& v, int n) {
  return std::all_of(v.begin(), v.end(), [n](int i) { return i < n; });
}

TEST(RigidMotionChoice, TheStaticWorldWinsOverALargerVehicleBesideAWall) {
  // Static: wall returns far ahead and behind (only what the clique can tell apart from traffic);
  // a vehicle in the next lane moves 1 m further than the ego vehicle in this scan.
  std::mt19937 rng(3);
  const mrpt::math::TPose2D ego(2.75, 0.0, 0.0), vehicle(3.75, 0.0, 0.0);
  Correspondences matches;
  addRigidSet(matches, ego, 8, 20, 60, 4, 6, rng);
  addRigidSet(matches, ego, 8, -60, -20, 4, 6, rng);
  const int n_static = static_cast<int>(matches.size());
  addRigidSet(matches, vehicle, 22, -2, 2, -4, -2, rng);
  const DenseGraph g = buildConsistencyGraph(matches, kDeltaC);
  const CliqueResult first = maximumClique(g);
  ASSERT_FALSE(allBelow(first.vertices, n_static))
      << "the scenario needs the vehicle to be the maximum clique";

  const RigidMotionChoice choice =
      chooseRigidMotion(matches, g, first.vertices, prediction(ego), kMinInliers, 0);
  EXPECT_TRUE(choice.second);
  EXPECT_TRUE(allBelow(choice.vertices, n_static));
  EXPECT_GE(static_cast<int>(choice.vertices.size()), n_static - 2);

  // Predicted at the vehicle's motion (the slide already under way), the vehicle keeps it: the choice
  // follows the likelihood, not a preference for the smaller set.
  expectFirstKept(matches, g, first, prediction(vehicle));
}

TEST(RigidMotionChoice, ALargerStaticWorldKeepsTheMaximumClique) {
  // The usual street: most matches static; a vehicle of 12 matches moving with the prediction's
  // error still loses, because the static set explains many more matches.
  std::mt19937 rng(5);
  const mrpt::math::TPose2D ego(2.0, 0.1, 0.01), vehicle(2.3, 0.1, 0.01);
  Correspondences matches;
  addRigidSet(matches, ego, 60, -60, 60, -60, 60, rng);
  addRigidSet(matches, vehicle, 12, -2, 2, -4, -2, rng);
  const DenseGraph g = buildConsistencyGraph(matches, kDeltaC);
  const CliqueResult first = maximumClique(g);
  // Predicted exactly at the vehicle's motion: still the static world.
  expectFirstKept(matches, g, first, prediction(vehicle));
}

TEST(RigidMotionChoice, NoSecondRigidSetOrNoPredictionKeepsTheFirst) {
  std::mt19937 rng(7);
  const mrpt::math::TPose2D ego(2.0, 0.0, 0.0);
  Correspondences matches;
  addRigidSet(matches, ego, 30, -40, 40, -40, 40, rng);
  std::uniform_real_distribution<double> u(-40, 40);
  for (int i = 0; i < 15; ++i) {  // scattered wrong matches: no rigid set of kMinInliers
    Correspondence m;
    m.cur = {u(rng), u(rng)};
    m.ref = {u(rng), u(rng)};
    matches.push_back(m);
  }
  const DenseGraph g = buildConsistencyGraph(matches, kDeltaC);
  const CliqueResult first = maximumClique(g);
  expectFirstKept(matches, g, first, prediction({9, 9, 0}));
  MotionPrediction none = prediction(ego);
  none.sigma_m = 0;  // the prediction's error not measured yet
  expectFirstKept(matches, g, first, none);
}

TEST(RigidMotionChoice, LogLikelihoodGrowsWithMatchesAndFallsWithTheDeviation) {
  const MotionPrediction p = prediction({2, 0, 0});
  const double base = rigidMotionLogLikelihood({2, 0, 0}, 20, p);
  EXPECT_GT(rigidMotionLogLikelihood({2, 0, 0}, 21, p), base);
  EXPECT_LT(rigidMotionLogLikelihood({2.3, 0, 0}, 20, p), base);
  EXPECT_DOUBLE_EQ(rigidMotionLogLikelihood({2.3, 0, 0}, 20, p),
                   rigidMotionLogLikelihood({2, -0.3, 0}, 20, p));
  // The value: 20 ln(R^2 / 4 sigma_k^2) - ln(2 pi s^2) at zero deviation, s^2 = sigma_t^2 + 2 sigma_k^2 / 20.
  const double s2 = 0.12 * 0.12 + 2 * 0.25 * 0.25 / 20;
  EXPECT_NEAR(base, 20 * std::log(1.1 * 1.1 / (4 * 0.25 * 0.25)) - std::log(2 * std::numbers::pi * s2), 1e-9);
}

}  // namespace
}  // namespace radarslam
