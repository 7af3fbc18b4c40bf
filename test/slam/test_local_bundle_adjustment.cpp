// Local bundle adjustment (paper Sec. III-B) on synthetic keyframes and landmarks: noisy initial
// poses are pulled back to the truth by the observations, fixed poses do not move, a gross
// outlier observation is absorbed by the Huber kernel.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "radarslam/slam/local_bundle_adjustment.h"
#include "radarslam/slam/slam_params.h"

namespace radarslam {
namespace {

using mrpt::math::TPose2D;

Eigen::Vector2d toLocal(const TPose2D& p, const Eigen::Vector2d& w) {
  const double c = std::cos(p.phi), s = std::sin(p.phi), dx = w.x() - p.x, dy = w.y() - p.y;
  return {c * dx + s * dy, -s * dx + c * dy};
}
TPose2D relative(const TPose2D& a, const TPose2D& b) {
  const Eigen::Vector2d t = toLocal(a, {b.x, b.y});
  return {t.x(), t.y(), std::remainder(b.phi - a.phi, 2 * M_PI)};
}

struct Scenario {
  std::vector<TPose2D> truth;
  std::vector<Eigen::Vector2d> landmarks;
  BAProblem problem;
};

/// 6 keyframes 2.5 m apart on a gentle curve, 200 landmarks around, every landmark within 60 m
/// seen by every keyframe with 5 cm noise; initial poses perturbed by up to 0.5 m / 1 degree,
/// landmarks initialised from the perturbed first observer.
Scenario makeScenario(std::uint32_t seed, double obs_noise = 0.05) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-50, 60);
  Scenario s;
  for (int k = 0; k < 6; ++k) s.truth.push_back({2.5 * k, 0.02 * k * k, 0.01 * k});
  for (int j = 0; j < 200; ++j) s.landmarks.emplace_back(u(rng), u(rng));
  auto& pb = s.problem;
  for (std::size_t k = 0; k < s.truth.size(); ++k) {
    TPose2D p = s.truth[k];
    if (k > 0) p = {p.x + 0.25 * n(rng), p.y + 0.25 * n(rng), p.phi + 0.01 * n(rng)};
    pb.poses.push_back(p);
    pb.fixed.push_back(k == 0);
  }
  for (std::size_t j = 0; j < s.landmarks.size(); ++j) {
    bool first = true;
    for (std::size_t k = 0; k < s.truth.size(); ++k) {
      Eigen::Vector2d z = toLocal(s.truth[k], s.landmarks[j]);
      if (z.norm() > 60) continue;
      z += obs_noise * Eigen::Vector2d(n(rng), n(rng));
      if (first) {
        const auto& p = pb.poses[k];
        pb.points.emplace_back(p.x + std::cos(p.phi) * z.x() - std::sin(p.phi) * z.y(),
                               p.y + std::sin(p.phi) * z.x() + std::cos(p.phi) * z.y());
        first = false;
      }
      pb.observations.push_back({k, pb.points.size() - 1, z});
    }
  }
  for (std::size_t k = 1; k < s.truth.size(); ++k)
    pb.priors.push_back({k - 1, k, relative(s.truth[k - 1], s.truth[k])});
  return s;
}

double maxPoseError(const std::vector<TPose2D>& a, const std::vector<TPose2D>& b) {
  double e = 0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::hypot(a[i].x - b[i].x, a[i].y - b[i].y));
  return e;
}

TEST(LocalBundleAdjustment, RecoversPosesFromNoisyStart) {
  Scenario s = makeScenario(1);
  const double before = maxPoseError(s.problem.poses, s.truth);
  ASSERT_GT(before, 0.2);
  LocalMappingParams params;
  params.max_iterations = 20;
  const BAReport r = solveLocalBundleAdjustment(s.problem, params);
  EXPECT_LT(r.final_cost, r.initial_cost);
  EXPECT_LT(maxPoseError(s.problem.poses, s.truth), 0.03);
  for (std::size_t k = 0; k < s.truth.size(); ++k)
    EXPECT_NEAR(std::remainder(s.problem.poses[k].phi - s.truth[k].phi, 2 * M_PI), 0.0, 0.002) << k;
  EXPECT_EQ(s.problem.poses[0].x, s.truth[0].x);  // fixed
}

TEST(LocalBundleAdjustment, FixedPosesDoNotMove) {
  Scenario s = makeScenario(2);
  s.problem.fixed = {true, true, false, false, false, true};
  const auto fixed_before = s.problem.poses;
  solveLocalBundleAdjustment(s.problem, {});
  for (const std::size_t k : {0u, 1u, 5u}) {
    EXPECT_EQ(s.problem.poses[k].x, fixed_before[k].x);
    EXPECT_EQ(s.problem.poses[k].phi, fixed_before[k].phi);
  }
}

TEST(LocalBundleAdjustment, GrossOutliersDoNotPullTheSolution) {
  Scenario s = makeScenario(3);
  // 5 % of the observations 5 m off.
  for (std::size_t i = 0; i < s.problem.observations.size(); i += 20) s.problem.observations[i].z.x() += 5.0;
  LocalMappingParams params;
  params.max_iterations = 30;
  const BAReport r = solveLocalBundleAdjustment(s.problem, params);
  EXPECT_LT(maxPoseError(s.problem.poses, s.truth), 0.08);
  EXPECT_GE(r.outliers, s.problem.observations.size() / 20 - 2);
}

}  // namespace
}  // namespace radarslam
