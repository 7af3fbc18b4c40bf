// The real Oxford route mode: the chained ground truth as the route, its real scan times, and the
// world generated around it.
#include <gtest/gtest.h>

#include "radarslam/core/trajectory.h"
#include "radarslam/sim/gt_route.h"
#include "shared_data.h"
#include "sim_test_util.h"

using namespace radarslam;
using namespace radarslam::sim;

TEST(SimGroundTruthRoute, OxfordRouteHasTheRealLengthAndScanCount) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_2019-01-10-11-46-21");
  const auto csv = dir / "gt" / "radar_odometry.csv";
  SimulationConfig cfg = simtest::smallConfig(1, 0);
  cfg.world_type = "oxford-route";
  cfg.route_from_gt = csv.string();
  const Simulation sim(cfg);
  EXPECT_EQ(sim.numScans(), 8866u);
  EXPECT_NEAR(sim.route().length(), 9020.0, 90.2);
  const Trajectory truth = sim.scanTruth();
  EXPECT_NEAR(pathLength(truth), 9020.0, 90.2);
  // The real scan times: the first scan starts at the file's first destination_radar_timestamp.
  EXPECT_EQ(sim.scanStart(0), 1547120787645464LL * kNsPerUs);
  // Stops: the real drive stands still for a while; a fixed-speed tour would not.
  std::size_t stopped = 0;
  for (std::size_t i = 1; i < truth.size(); ++i)
    stopped +=
        std::hypot(truth[i].pose.x - truth[i - 1].pose.x, truth[i].pose.y - truth[i - 1].pose.y) < 0.01;
  EXPECT_GT(stopped, 100u);
  // The world around it: objects all along, none on the road.
  EXPECT_GT(sim.world().segments.size(), 5000u);
  const GroundTruthRoute g = routeFromOxfordGroundTruth(csv, cfg.route, 1, cfg.route_world.road_half_width_m);
  RoadIndex index(g.roads);
  for (const auto& c : sim.world().circles)
    ASSERT_GT(index.clearance(c.centre) - c.radius, cfg.route_world.margin_m);
}
