// Message conversions and in-process publish/subscribe through the RAII layer (loopback domain).
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <cmath>

#include <radarslam/core/errors.h>
#include <radarslam/dds/domain.h>
#include <radarslam/dds/map_messages.h>
#include <radarslam/dds/pose_publisher.h>
#include <radarslam/dds/scan_messages.h>
#include <radarslam/dds/scan_subscriber.h>

#include "dds_test_util.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

using namespace std::chrono_literals;

CObservationRadarScan::Ptr randomScan(unsigned seed) {
  auto scan = CObservationRadarScan::Create();
  scan->resize(40, 100);
  scan->range_resolution_m = 0.0438;
  scan->range_offset_m = 0.0219;
  std::mt19937 rng(seed);
  for (auto& p : scan->power) p = static_cast<std::uint8_t>(rng());
  for (std::uint32_t a = 0; a < 40; ++a)
    scan->azimuth_stamps_ns[a] = 1'600'000'000'123'456'789LL + a * 625'000LL;
  scan->azimuth_valid[7] = 0;
  scan->updateReferenceTime();
  return scan;
}

void expectSameScan(const CObservationRadarScan& a, const CObservationRadarScan& b) {
  EXPECT_EQ(a.num_azimuths, b.num_azimuths);
  EXPECT_EQ(a.num_bins, b.num_bins);
  EXPECT_EQ(a.range_resolution_m, b.range_resolution_m);
  EXPECT_EQ(a.range_offset_m, b.range_offset_m);
  EXPECT_EQ(a.power, b.power);
  EXPECT_EQ(a.azimuth_stamps_ns, b.azimuth_stamps_ns);
  EXPECT_EQ(a.azimuth_angles_rad, b.azimuth_angles_rad);
  EXPECT_EQ(a.azimuth_valid, b.azimuth_valid);
  EXPECT_EQ(a.refStampNs(), b.refStampNs());
}

TEST(DdsMessages, TimeConversionHandlesNegativeAndLargeStamps) {
  for (StampNs t :
       {StampNs{0}, StampNs{1'700'000'000'123'456'789LL}, StampNs{-1}, StampNs{-1'500'000'001LL}}) {
    const auto m = dds::toTimeMsg(t);
    EXPECT_LT(m.nanosec, 1'000'000'000u);
    EXPECT_EQ(dds::fromTimeMsg(m), t);
  }
}

TEST(DdsMessages, RadarScanRoundTripsThroughDds) {
  dds::Domain dom(test::testDomainId(6));
  dds::ScanSubscriber sub(dom, dds::kRadarScanTopic, 8);
  dds::Publisher<dds::RadarScanMsg> pub(dom, dds::kRadarScanTopic, dds::TopicQos::stream(8));
  ASSERT_TRUE(pub.waitForSubscriptions(1, 5s));
  const auto sent = randomScan(1);
  pub.publish(dds::scanMessage(*sent, "navtech"));
  const auto got = sub.next(5s);
  ASSERT_TRUE(got);
  expectSameScan(*sent, *got);
  EXPECT_EQ(got->sensorLabel, "navtech");
  EXPECT_FALSE(sub.next(50ms));  // nothing else was sent
}

TEST(DdsMessages, MalformedRadarScanIsRejected) {
  auto msg = dds::scanMessage(*randomScan(2));
  msg.power.pop_back();
  EXPECT_THROW(dds::scanFromMessage(msg), InputError);
  msg = dds::scanMessage(*randomScan(2));
  msg.azimuth_angles.resize(3);
  EXPECT_THROW(dds::scanFromMessage(msg), InputError);
}

TEST(DdsMessages, PosePublisherSendsAPlanarPoseWithCovariance) {
  dds::Domain dom(test::testDomainId(7));
  dds::Subscription<dds::PoseWithCovarianceStampedMsg> sub(dom, dds::kPoseTopic, dds::TopicQos::stream(10));
  dds::PosePublisher pub(dom);
  const std::array<double, 9> cov{0.01, 0.002, 0.0, 0.002, 0.02, 0.0, 0.0, 0.0, 0.003};
  const mrpt::math::TPose2D pose(12.5, -3.25, 2.9);
  pub.publish(1'700'000'000'500'000'000LL, pose, cov);
  const auto got = sub.take(5s);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->header.frame_id, "map");
  EXPECT_EQ(dds::fromTimeMsg(got->header.stamp), 1'700'000'000'500'000'000LL);
  const auto back = dds::poseFromMessage(*got);
  EXPECT_DOUBLE_EQ(back.x, 12.5);
  EXPECT_DOUBLE_EQ(back.y, -3.25);
  EXPECT_NEAR(back.phi, 2.9, 1e-12);
  EXPECT_DOUBLE_EQ(got->covariance[0 * 6 + 1], 0.002);  // x-y
  EXPECT_DOUBLE_EQ(got->covariance[1 * 6 + 1], 0.02);   // y-y
  EXPECT_DOUBLE_EQ(got->covariance[5 * 6 + 5], 0.003);  // yaw-yaw
  EXPECT_DOUBLE_EQ(got->covariance[2 * 6 + 2], 1e6);    // z: not estimated
}

TEST(DdsMessages, GridMessageMatchesTheOccupancyRaster) {
  const KeyframeMap map = test::syntheticMap(3, 100, 20.0, 8);
  const OccupancyRaster r = buildOccupancy(map);
  const auto g = dds::gridMessage(map, {}, 42);
  ASSERT_EQ(g.width, static_cast<std::uint32_t>(r.width));
  ASSERT_EQ(g.height, static_cast<std::uint32_t>(r.height));
  EXPECT_FLOAT_EQ(g.resolution, 0.2f);
  EXPECT_DOUBLE_EQ(g.origin.x, r.x_min);
  EXPECT_DOUBLE_EQ(g.origin.y, r.y_min);
  ASSERT_EQ(g.data.size(), r.p_occupied.size());
  int unknown = 0;
  for (std::size_t i = 0; i < g.data.size(); ++i) {
    if (!r.observed[i]) {
      EXPECT_EQ(g.data[i], -1);
      ++unknown;
    } else {
      EXPECT_NEAR(g.data[i], 100.0 * r.p_occupied[i], 0.5 + 1e-6);
    }
  }
  EXPECT_GT(unknown, 0);
  EXPECT_LT(unknown, static_cast<int>(g.data.size()));
  auto bad = g;
  bad.data.pop_back();
  test::TempDir tmp;
  EXPECT_THROW(dds::writeGridFiles(bad, tmp.path()), InputError);
}

TEST(DdsMessages, CloudAndOctomapMessagesWriteValidFiles) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap(2, 80, 15.0, 9);
  const auto cloud = dds::cloudMessage(map, 0);
  EXPECT_EQ(cloud.width, 2u * 84u);
  EXPECT_EQ(cloud.data.size(), cloud.width * 16u);
  dds::writePcdFile(cloud, tmp.path() / "c.pcd");
  EXPECT_NE(test::readText(tmp.path() / "c.pcd").find("POINTS 168\n"), std::string::npos);

  const auto octo = dds::octomapMessage(map, {}, 0);
  EXPECT_FALSE(octo.data.empty());
  dds::writeOctomapFile(octo, tmp.path() / "m.bt");
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary((tmp.path() / "m.bt").string()));
  EXPECT_DOUBLE_EQ(tree.getResolution(), 0.2);
  EXPECT_GT(tree.size(), 100u);
  auto bad = octo;
  bad.id = "ColorOcTree";
  EXPECT_THROW(dds::writeOctomapFile(bad, tmp.path() / "x.bt"), InputError);
}

TEST(DdsDomain, BadDomainIdAndConfigAreInputErrors) {
  EXPECT_THROW(dds::Domain(dds::kMaxDomainId + 1), InputError);
  EXPECT_THROW(dds::Domain(test::testDomainId(8), "<CycloneDDS><Domain><Nonsense/></Domain></CycloneDDS>"),
               InputError);
  test::TempDir tmp;
  EXPECT_THROW(dds::readConfigFile(tmp.path() / "none.xml"), InputError);
  std::ofstream(tmp.path() / "x.xml") << "<html/>";
  EXPECT_THROW(dds::readConfigFile(tmp.path() / "x.xml"), InputError);
  // The shipped configuration parses and works.
  const auto xml = dds::readConfigFile(std::filesystem::path(RADARSLAM_SOURCE_DIR) / "config" / "dds.xml");
  dds::Domain dom(test::testDomainId(8), xml);
  EXPECT_GT(dom.participant(), 0);
}

}  // namespace
}  // namespace radarslam

namespace radarslam {
namespace {

// ROS 2 (rmw_cyclonedds) matches by these exact type names; rt/ is the ROS 2 topic prefix.
TEST(DdsMessages, TypeAndTopicNamesFollowRos2Conventions) {
  EXPECT_EQ(dds::ddsTypeName<dds::OccupancyGridMsg>(), "nav_msgs::msg::dds_::OccupancyGrid_");
  EXPECT_EQ(dds::ddsTypeName<dds::PointCloud2Msg>(), "sensor_msgs::msg::dds_::PointCloud2_");
  EXPECT_EQ(dds::ddsTypeName<dds::OctomapMsg>(), "octomap_msgs::msg::dds_::Octomap_");
  EXPECT_EQ(dds::ddsTypeName<dds::PoseWithCovarianceStampedMsg>(),
            "geometry_msgs::msg::dds_::PoseWithCovarianceStamped_");
  EXPECT_EQ(dds::ddsTypeName<dds::MapInfoMsg>(), "radarslam::msg::dds_::MapInfo_");
  EXPECT_EQ(dds::ddsTypeName<dds::RadarScanMsg>(), "radarslam::msg::dds_::RadarScan_");
  EXPECT_STREQ(dds::kMapTopic, "rt/map");
}

}  // namespace
}  // namespace radarslam
