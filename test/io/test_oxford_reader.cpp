// Oxford Radar RobotCar reader and ground truth on the real data in ../shared.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/ground_truth.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;

TEST(OxfordReader, TinySequenceDecodesWithItsOwnGeometryAndTimes) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  const auto reader = openDataset(dir);
  EXPECT_EQ(reader->kind(), DatasetKind::Oxford);
  ASSERT_EQ(reader->size(), 11u);
  for (std::size_t i = 0; i < reader->size(); ++i) {
    SCOPED_TRACE(i);
    const auto scan = reader->readScan(i);
    EXPECT_EQ(scan->checkConsistency(), "");
    EXPECT_EQ(scan->num_azimuths, 400u);
    EXPECT_EQ(scan->num_bins, 3768u);
    EXPECT_DOUBLE_EQ(scan->range_resolution_m, 0.0432);
    EXPECT_DOUBLE_EQ(scan->range_offset_m, 0.0216);
    // File name (us) == the first azimuth's stamp; the index stamp is that file name.
    EXPECT_EQ(reader->scanPath(i).stem().string(), std::to_string(scan->azimuth_stamps_ns.front() / 1000));
    EXPECT_EQ(reader->indexStamp(i), scan->azimuth_stamps_ns.front());
    const double mean_step_ms =
        toSeconds(scan->azimuth_stamps_ns.back() - scan->azimuth_stamps_ns.front()) * 1e3 / 399.0;
    EXPECT_NEAR(mean_step_ms, 0.625, 0.02);
    for (std::size_t a = 1; a < scan->num_azimuths; ++a) {
      EXPECT_GT(scan->azimuth_stamps_ns[a], scan->azimuth_stamps_ns[a - 1]);
      EXPECT_NEAR(scan->azimuth_angles_rad[a] - scan->azimuth_angles_rad[a - 1], 0.9 * std::numbers::pi / 180,
                  1e-9);
    }
    EXPECT_EQ(std::count(scan->azimuth_valid.begin(), scan->azimuth_valid.end(), 1), 400);
    EXPECT_EQ(scan->refStampNs(), scan->azimuth_stamps_ns.front() / 2 + scan->azimuth_stamps_ns.back() / 2);
  }
  // A single file decodes the same on its own (the dataset is found from its folder).
  EXPECT_EQ(readScanFile(reader->scanPath(7))->power, reader->readScan(7)->power);
}

TEST(OxfordReader, GroundTruthRowsMatchScansAndChainIntoForwardMotion) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  const auto reader = openDataset(dir);
  ASSERT_TRUE(reader->hasGroundTruth());
  const auto rows = readOxfordOdometryRows(dir / "gt" / "radar_odometry.csv");
  for (std::size_t i = 1; i < reader->size(); ++i) {
    SCOPED_TRACE(i);
    const auto row = std::find_if(rows.begin(), rows.end(), [&](const OxfordOdometryRow& r) {
      return r.source_radar == reader->indexStamp(i) && r.destination_radar == reader->indexStamp(i - 1);
    });
    ASSERT_NE(row, rows.end()) << "no GT row for scan pair";
    const auto prev = reader->readScan(i - 1), cur = reader->readScan(i);
    // GT times are mid-sweep: within a few ms of the scans' reference times.
    EXPECT_NEAR(toSeconds(row->source - cur->refStampNs()), 0.0, 0.005);
    EXPECT_NEAR(toSeconds(row->destination - prev->refStampNs()), 0.0, 0.005);
    const auto a = reader->groundTruthAt(prev->refStampNs()), b = reader->groundTruthAt(cur->refStampNs());
    ASSERT_TRUE(a && b);
    const mrpt::math::TPose2D rel = *b - *a;  // pose of scan i in scan i-1
    EXPECT_GT(rel.x, 1.5);
    EXPECT_LT(rel.x, 2.6);
    EXPECT_LT(std::abs(rel.y), 0.3);
    EXPECT_LT(std::abs(rel.phi), 0.05);
    // And it is the row itself (the chain reproduces the relative motion).
    EXPECT_NEAR(rel.x, row->motion.x, 0.05);
  }
}

TEST(OxfordGroundTruth, Full9kmSequenceChainsWithoutGaps) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_2019-01-10-11-46-21");
  const auto gt = readOxfordGroundTruth(dir / "gt" / "radar_odometry.csv");
  ASSERT_EQ(gt.size(), 8866u);  // 8865 rows + the identity at the first destination time
  EXPECT_FALSE(firstNonIncreasingStamp(gt).has_value());
  EXPECT_NEAR(pathLength(gt) / 1000.0, 9.02, 0.1);
  EXPECT_EQ(gt.front().pose, mrpt::math::TPose2D(0, 0, 0));
  // The one scan present (#664, 1-based) is indexed from radar.timestamps and decodes.
  const auto reader = openDataset(dir);
  ASSERT_EQ(reader->size(), 8867u);
  EXPECT_EQ(reader->scanPath(663).filename(), "1547120953445209.png");
  const auto scan = reader->readScan(663);
  EXPECT_EQ(scan->azimuth_stamps_ns.front(), 1547120953445209000LL);
  EXPECT_TRUE(reader->groundTruthAt(scan->refStampNs()).has_value());
}

TEST(OxfordGroundTruth, ChainComposesRelativeRows) {
  // Two synthetic rows: 1 m forward, then 1 m forward after turning 90 deg left.
  std::vector<OxfordOdometryRow> rows(2);
  rows[0].source = 2000, rows[0].destination = 1000, rows[0].motion = {1, 0, std::numbers::pi / 2};
  rows[1].source = 3000, rows[1].destination = 2000, rows[1].motion = {1, 0, 0};
  const auto traj = chainOxfordOdometry(rows, "synthetic.csv");
  ASSERT_EQ(traj.size(), 3u);
  EXPECT_EQ(traj[0].stamp, 1000);
  EXPECT_NEAR(traj[2].pose.x, 1.0, 1e-12);
  EXPECT_NEAR(traj[2].pose.y, 1.0, 1e-12);
  EXPECT_NEAR(traj[2].pose.phi, std::numbers::pi / 2, 1e-12);
  rows[1].destination = 2500;
  test::expectInputError([&] { chainOxfordOdometry(rows, "synthetic.csv"); }, "synthetic.csv:3",
                         "ground-truth gap");
}
