// M2DP's defining properties on synthetic point worlds: rigid-motion and point-order invariance,
// deterministic sign handling, distinctiveness of places and robustness to point dropout.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/loop/m2dp.h"
#include "synthetic_world.h"

namespace radarslam {
namespace {

using looptest::observe;
using looptest::randomWorld;
using looptest::transformed;

TEST(M2DP, HasTheShapeOfUAndVAndUnitHalves) {
  const auto cloud = observe(randomWorld(1), 0, 0, 0, 1);
  const M2DPParams p;
  const auto d = computeM2DP(cloud, p);
  ASSERT_EQ(d.size(), p.azimuths * p.elevations + p.rings * p.sectors);
  EXPECT_NEAR(d.head(p.azimuths * p.elevations).norm(), 1.0, 1e-5);
  EXPECT_NEAR(d.tail(p.rings * p.sectors).norm(), 1.0, 1e-5);
  EXPECT_GE(d.tail(p.rings * p.sectors).sum(), 0.f);                                  // SVD sign convention
  EXPECT_EQ(computeM2DP(std::span<const RadarPoint>(cloud.data(), 5), p).size(), 0);  // too few points
}

TEST(M2DP, InvariantToRotationAndTranslationOfTheCloud) {
  const auto cloud = observe(randomWorld(2), 10, -5, 0.3, 2);
  const auto d0 = computeM2DP(cloud);
  for (double yaw : {0.5, M_PI / 2, M_PI, 4.0, 5.9}) {
    const auto d = computeM2DP(transformed(cloud, 13.0, -7.5, yaw));
    EXPECT_LT(m2dpDistance(d0, d), 0.01) << "yaw " << yaw;
  }
}

TEST(M2DP, InvariantToPointOrderAndDeterministic) {
  auto cloud = observe(randomWorld(3), 0, 0, 0, 3);
  const auto d0 = computeM2DP(cloud);
  EXPECT_EQ(m2dpDistance(d0, computeM2DP(cloud)), 0.f);
  std::shuffle(cloud.begin(), cloud.end(), std::mt19937(7));
  EXPECT_LT(m2dpDistance(d0, computeM2DP(cloud)), 1e-4);
}

TEST(M2DP, FirstAxisSignIsResolvedAndTheOtherSignIsAvailable) {
  const auto cloud = observe(randomWorld(4), 0, 0, 0, 4);
  const auto d = computeM2DP(cloud), flipped = computeM2DP(cloud, {}, true);
  // The flipped descriptor is a different one (the cloud is not point-symmetric) ...
  EXPECT_GT(m2dpDistance(d, flipped), 0.05);
  // ... and it is what the cloud turned by 180 degrees gives with the flip, while without the
  // flip the turned cloud gives d (the sign follows the cloud's third moment, not the frame).
  const auto turned = transformed(cloud, 0, 0, M_PI);
  EXPECT_LT(m2dpDistance(computeM2DP(turned), d), 0.01);
  EXPECT_LT(m2dpDistance(computeM2DP(turned, {}, true), flipped), 0.01);
}

// Re-observations of a place (new scan: resampled points, noise, dropout; moved 2 m, any heading)
// are much closer than observations of other places.
TEST(M2DP, SamePlaceCloseDifferentPlacesFar) {
  const auto world = randomWorld(5);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-150, 150), yaw(-M_PI, M_PI);
  std::vector<M2DPDescriptor> first, second;
  for (unsigned i = 0; i < 20; ++i) {
    const double x = pos(rng), y = pos(rng);
    first.push_back(computeM2DP(observe(world, x, y, yaw(rng), 100 + i)));
    second.push_back(computeM2DP(observe(world, x + 1.5, y - 1.3, yaw(rng), 200 + i)));
  }
  int nearest_is_self = 0;
  double same = 0, diff = 0;
  int n_diff = 0;
  for (std::size_t i = 0; i < first.size(); ++i) {
    std::size_t best = 0;
    for (std::size_t j = 0; j < first.size(); ++j) {
      const float dist = m2dpDistance(second[i], first[j]);
      if (dist < m2dpDistance(second[i], first[best])) best = j;
      if (i == j)
        same += dist;
      else
        diff += dist, ++n_diff;
    }
    nearest_is_self += best == i;
  }
  same /= static_cast<double>(first.size());
  diff /= n_diff;
  EXPECT_GE(nearest_is_self, 18);
  EXPECT_GT(diff, 3 * same) << "same " << same << " different " << diff;
}

// M2DP counts points per bin, so dropping points adds sampling noise: on ~1000-point clouds (the
// size of an Oxford peak cloud) 20 % dropout moves the descriptor by 0.05-0.26 while other places
// are 0.6-1.4 away (measured over seeds 6-9).
TEST(M2DP, RobustToTwentyPercentDropout) {
  const auto world = randomWorld(6);
  const auto cloud = observe(world, 0, 0, 0, 6, 80, 4.0);
  ASSERT_GT(cloud.size(), 800u);
  const auto other_place = computeM2DP(observe(world, 120, 80, 0, 7, 80, 4.0));
  const auto d0 = computeM2DP(cloud);
  std::mt19937 rng(8);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<RadarPoint> kept;
    for (const auto& p : cloud)
      if (std::uniform_real_distribution<double>(0, 1)(rng) >= 0.2) kept.push_back(p);
    const float dist = m2dpDistance(d0, computeM2DP(kept));
    EXPECT_LT(dist, 0.3);
    EXPECT_LT(dist, 0.4 * m2dpDistance(d0, other_place));
  }
}

TEST(M2DP, ParamsFromYamlAndBadValuesRejected) {
  M2DPParams p;
  loadParams(YamlParams::fromText("rings: 6\nsectors: 12\npower_height_m: 0\n"), p);
  EXPECT_EQ(p.rings, 6);
  EXPECT_EQ(p.sectors, 12);
  const auto d = computeM2DP(observe(randomWorld(9), 0, 0, 0, 9), p);
  EXPECT_EQ(d.size(), p.azimuths * p.elevations + 6 * 12);
  EXPECT_THROW(loadParams(YamlParams::fromText("rings: 0\n"), p), InputError);
}

}  // namespace
}  // namespace radarslam
