// radarslam-scan-publisher as a separate process feeding a ScanSubscriber (the localiser's DDS
// scan source) in this process.
#include <gtest/gtest.h>

#include <radarslam/dds/scan_subscriber.h>
#include <radarslam/io/dataset.h>
#include <radarslam/io/oxford_writer.h>
#include <radarslam/obs/registration.h>

#include "dds_test_util.h"
#include "synthetic_oxford.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

using namespace std::chrono_literals;

TEST(ScanPublisher, ReplaysADatasetToAScanSubscriber) {
  registerRadarslamClasses();
  test::TempDir tmp;
  const auto dir = tmp.path() / "ds";
  test::writeNoiseOxfordDataset(dir, 5, 3);
  const auto reader = openDataset(dir);
  ASSERT_EQ(reader->size(), 5u);

  const unsigned dom_id = test::testDomainId(9);
  dds::Domain dom(dom_id);
  dds::ScanSubscriber sub(dom, dds::kRadarScanTopic, 16);
  test::Child pub({RADARSLAM_SCAN_PUBLISHER, dir.string(), "--domain", std::to_string(dom_id), "--rate", "0",
                   "--wait-subscribers", "1", "--wait-timeout", "10"},
                  tmp.path() / "publisher");
  for (std::size_t i = 0; i < 5; ++i) {
    const auto got = sub.next(10s);
    ASSERT_TRUE(got) << "scan " << i << ": " << pub.err();
    const auto want = reader->readScan(i);
    EXPECT_EQ(got->power, want->power);
    EXPECT_EQ(got->azimuth_stamps_ns, want->azimuth_stamps_ns);
    EXPECT_EQ(got->azimuth_angles_rad, want->azimuth_angles_rad);
    EXPECT_EQ(got->range_resolution_m, want->range_resolution_m);
    EXPECT_EQ(got->refStampNs(), want->refStampNs());
  }
  EXPECT_EQ(pub.wait(15), 0) << pub.err();
  EXPECT_NE(pub.out().find("published 5 scans"), std::string::npos);
  EXPECT_FALSE(sub.next(100ms));
}

TEST(ScanPublisher, MissingDatasetIsAOneLineError) {
  test::TempDir tmp;
  test::Child pub({RADARSLAM_SCAN_PUBLISHER, (tmp.path() / "nothing").string()}, tmp.path() / "p");
  ASSERT_EQ(pub.wait(15), 1) << pub.err();
  const std::string e = pub.err();
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
  EXPECT_NE(e.find("nothing"), std::string::npos) << e;
}

}  // namespace
}  // namespace radarslam
