// Keyframe insertion shared by SLAM and map-synth: policy thresholds, ids, odometry edges whose
// relative pose composes back to the keyframe pose.
#include <gtest/gtest.h>
#include <mrpt/poses/CPose2D.h>

#include <cmath>

#include "radarslam/map/map_from_trajectory.h"

using namespace radarslam;

TEST(MapFromTrajectory, KeyframePolicyAndOdometryEdges) {
  KeyframeMap map;
  KeyframeInsertionParams params;  // 2 m / 0.2 rad
  const mrpt::math::TPose2D p0{10, 5, 0.3};
  EXPECT_TRUE(needsKeyframe(map, p0, params));
  std::vector<RadarPoint> cloud(3);
  cloud[1].x = 4.f, cloud[1].y = -2.f, cloud[1].power = 99.f, cloud[1].range_m = 4.47f;
  EXPECT_EQ(addKeyframe(map, 100, p0, cloud), 0u);
  EXPECT_TRUE(map.edges.empty());
  EXPECT_FALSE(needsKeyframe(map, {11.5, 5.5, 0.35}, params));              // 1.58 m, 0.05 rad
  EXPECT_FALSE(needsKeyframe(map, {11.9, 5.0, 0.3}, params));               // 1.9 m
  EXPECT_TRUE(needsKeyframe(map, {12.0, 5.0, 0.3}, params));                // 2.0 m
  EXPECT_TRUE(needsKeyframe(map, {10, 5, 0.3 + 0.21}, params));             // angle
  EXPECT_TRUE(needsKeyframe(map, {10, 5, 0.3 - 2 * M_PI + 0.25}, params));  // angle across the wrap
  const mrpt::math::TPose2D p1{12.5, 6.0, 0.9};
  EXPECT_EQ(addKeyframe(map, 200, p1, cloud, {1.f, 2.f}), 1u);
  ASSERT_EQ(map.keyframes.size(), 2u);
  EXPECT_EQ(map.keyframes[1].points[1], (KeyframePoint{4.f, -2.f, 99.f}));
  EXPECT_EQ(map.keyframes[1].descriptor.size(), 2u);
  ASSERT_EQ(map.edges.size(), 1u);
  const auto& e = map.edges[0];
  EXPECT_EQ(e.from, 0u);
  EXPECT_EQ(e.to, 1u);
  EXPECT_EQ(e.kind, EdgeKind::Odometry);
  const auto composed = (mrpt::poses::CPose2D(p0) + mrpt::poses::CPose2D(e.relative)).asTPose();
  EXPECT_NEAR(composed.x, p1.x, 1e-12);
  EXPECT_NEAR(composed.y, p1.y, 1e-12);
  EXPECT_NEAR(composed.phi, p1.phi, 1e-12);
  EXPECT_EQ(e.information[0], params.odometry_information[0]);
  EXPECT_EQ(e.information[8], params.odometry_information[2]);
}
