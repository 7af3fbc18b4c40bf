// The simulated vehicle turns like a car: curvature ramps into each turn (no step), the speed
// profile respects yaw-rate and yaw-acceleration limits, and the yaw-rate / yaw-acceleration
// distribution of the grid and network routes is within x1.5 of the real Oxford drive's.
#include <gtest/gtest.h>

#include <cstdio>

#include "radarslam/eval/yaw_dynamics.h"
#include "radarslam/io/ground_truth.h"
#include "radarslam/sim/route.h"
#include "radarslam/sim/street_network.h"
#include "radarslam/sim/world.h"
#include "shared_data.h"
#include "sim_test_util.h"

using namespace radarslam;
using namespace radarslam::sim;

namespace {
constexpr double kScanPeriodS = 0.25;  // the Oxford radar's 4 Hz: the real ground truth's spacing

eval::YawDynamics gridRoute(std::uint64_t seed, const RouteParams& p) {
  return eval::yawDynamics(
      simtest::sampleTrajectory(planRoute(generateWorld({}, seed, 1), p, seed, 1), kScanPeriodS));
}

eval::YawDynamics networkRoute(std::uint64_t seed, const RouteParams& p) {
  return eval::yawDynamics(simtest::sampleTrajectory(
      planRouteThrough(generateStreetNetwork(seed, p).lap, p, seed, 1), kScanPeriodS));
}

void print(const char* what, const eval::YawDynamics& d) {
  std::printf("%-34s yaw rate p99 %5.1f max %5.1f deg/s; yaw acc p95 %5.1f p99 %5.1f max %6.1f deg/s^2\n",
              what, d.rate_p99_dps, d.rate_max_dps, d.accel_p95_dps2, d.accel_p99_dps2, d.accel_max_dps2);
}
}  // namespace

TEST(RouteDynamics, CurvatureRampsInsteadOfSteppingAtEveryTurn) {
  RouteParams stepped;
  stepped.curvature_transition_m = 0;
  stepped.max_yaw_rate_dps = 180;
  stepped.max_yaw_accel_dps2 = 1000;
  const RouteParams ramped;
  const eval::YawDynamics before = gridRoute(1, stepped), after = gridRoute(1, ramped);
  print("grid seed 1, circular fillets", before);
  print("grid seed 1, default", after);
  EXPECT_GT(before.accel_p99_dps2, 3 * ramped.max_yaw_accel_dps2);  // the fillets' curvature steps
  EXPECT_LT(after.accel_p99_dps2, 1.5 * ramped.max_yaw_accel_dps2);
  EXPECT_LT(after.rate_max_dps, 1.1 * ramped.max_yaw_rate_dps);
}

TEST(RouteDynamics, TheLimitsAreRespectedOnTheIrregularNetwork) {
  const RouteParams p;
  for (std::uint64_t seed : {11u, 12u, 13u}) {
    const eval::YawDynamics d = networkRoute(seed, p);
    print(("network seed " + std::to_string(seed)).c_str(), d);
    EXPECT_LT(d.rate_max_dps, 1.1 * p.max_yaw_rate_dps) << "seed " << seed;
    EXPECT_LT(d.accel_p99_dps2, 1.5 * p.max_yaw_accel_dps2) << "seed " << seed;
  }
}

TEST(RouteDynamics, WithinOneAndAHalfTimesTheRealOxfordDrive) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_2019-01-10-11-46-21");
  const eval::YawDynamics real = eval::yawDynamics(readOxfordGroundTruth(dir / "gt" / "radar_odometry.csv"));
  print("real Oxford 2019-01-10-11-46-21", real);
  const RouteParams p;
  // The distribution of each turn's dynamics within x1.5 both ways; the extremes not beyond x1.5.
  // (The p95 of the yaw acceleration is printed, not checked: it counts how often a route turns,
  // which is the street layout's, not the driving's.)
  auto within = [&](const eval::YawDynamics& sim, const std::string& what) {
    for (auto [s, r, name] : {std::tuple{sim.rate_p99_dps, real.rate_p99_dps, "yaw rate p99"},
                              std::tuple{sim.accel_p99_dps2, real.accel_p99_dps2, "yaw acceleration p99"}}) {
      EXPECT_LE(s, 1.5 * r) << what << ": " << name;
      EXPECT_GE(s, r / 1.5) << what << ": " << name;
    }
    EXPECT_LE(sim.rate_max_dps, 1.5 * real.rate_max_dps) << what;
    EXPECT_LE(sim.accel_max_dps2, 1.5 * real.accel_max_dps2) << what;
  };
  for (std::uint64_t seed : {1u, 2u, 4u}) {
    const eval::YawDynamics d = gridRoute(seed, p);
    print(("grid seed " + std::to_string(seed)).c_str(), d);
    within(d, "grid seed " + std::to_string(seed));
  }
  for (std::uint64_t seed : {11u, 21u, 23u}) {
    const eval::YawDynamics d = networkRoute(seed, p);
    print(("network seed " + std::to_string(seed)).c_str(), d);
    within(d, "network seed " + std::to_string(seed));
  }
}
