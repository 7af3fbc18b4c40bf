// MulRan: the real per-ray CSV scan, and synthetic polar_oxford_form / plain polar sequences and
// global_pose.csv ground truth written in the exact layouts.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/ground_truth.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;

TEST(MulRanRayCsv, RealScanDecodes) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "mulran_single_ray_scan");
  const auto file = dir / "1564718976161407002.csv";
  const auto scan = readScanFile(file);
  EXPECT_EQ(scan->checkConsistency(), "");
  EXPECT_EQ(scan->num_azimuths, 400u);
  EXPECT_EQ(scan->num_bins, 3360u);
  EXPECT_DOUBLE_EQ(scan->range_resolution_m, 0.05952);
  // MulRan stamps a scan at its end: the last azimuth's time is the file name.
  EXPECT_EQ(scan->azimuth_stamps_ns.back(), 1564718976161407002LL);
  EXPECT_EQ(scan->azimuth_stamps_ns.front(), 1564718975911638410LL);
  EXPECT_NEAR(scan->azimuth_angles_rad.front(), 9.0 / 5600 * 2 * std::numbers::pi, 1e-12);
  for (std::size_t a = 1; a < 400; ++a)
    EXPECT_NEAR(scan->azimuth_angles_rad[a] - scan->azimuth_angles_rad[a - 1], 0.9 * std::numbers::pi / 180,
                1e-9);
  EXPECT_EQ(scan->row(0)[0], 31);  // first range bin of the first line
}

TEST(MulRanRayCsv, MalformedRowsAreErrors) {
  test::TempDir tmp;
  const auto file = tmp / "1564718976161407002.csv";
  test::writeText(file, "1564718975911638410,0.57,9,1,1,2,3\n1564718975912638410,1.47,23,2,1,2\n");
  test::expectInputError([&] { readScanFile(file); }, "1564718976161407002.csv:2",
                         "6 fields, previous rows had 7");
  test::writeText(file, "1564718975911638410,0.57,9,1,1,2,3\n1564718975912638410,1.47,23,2,1,2,300\n");
  test::expectInputError([&] { readScanFile(file); }, ".csv:2", "outside 0..255");
  test::writeText(file, "1564718975911638410,0.57,9,1,1,2,3\n1564718975912638410,1.47,23,2,1,2,3\n");
  test::expectInputError([&] { readScanFile(file); }, "1564718976161407002.csv",
                         "not the last azimuth's timestamp");
}

namespace {
// A synthetic MulRan sequence: 3 scans of 40 azimuths x 50 bins, 250 ms apart, ns stamps.
constexpr StampNs kT0 = 1564718975911638410LL;
constexpr StampNs kAzStep = 6'250'000;  // 40 azimuths over 250 ms
constexpr int kAz = 40, kBins = 50;
StampNs lastAzimuth(int scan) { return kT0 + scan * 250'000'000LL + (kAz - 1) * kAzStep; }
}  // namespace

TEST(MulRanReader, OxfordFormSyntheticSequence) {
  test::TempDir tmp;
  for (int s = 0; s < 3; ++s) {
    const auto sweep = test::makeSweep(kAz, kT0 + s * 250'000'000LL, kAzStep, 9);
    test::writeOxfordStylePng(tmp / "polar_oxford_form" / (std::to_string(lastAzimuth(s)) + ".png"),
                              sweep.stamps, sweep.encoders, sweep.valid, kBins);
  }
  const auto reader = openDataset(tmp.path());
  EXPECT_EQ(reader->kind(), DatasetKind::MulRanOxfordForm);
  EXPECT_EQ(reader->sensorName(), "Navtech CIR204-H");
  ASSERT_EQ(reader->size(), 3u);
  EXPECT_FALSE(reader->hasGroundTruth());
  for (std::size_t s = 0; s < 3; ++s) {
    const auto scan = reader->readScan(s);
    EXPECT_EQ(scan->num_azimuths, static_cast<std::uint32_t>(kAz));
    EXPECT_EQ(scan->num_bins, static_cast<std::uint32_t>(kBins));
    EXPECT_DOUBLE_EQ(scan->range_resolution_m, 0.05952);
    EXPECT_EQ(reader->indexStamp(s), scan->azimuth_stamps_ns.back());  // end-stamped
    EXPECT_EQ(scan->azimuth_valid[0], 0);                              // valid byte 0 -> not valid
    EXPECT_EQ(scan->azimuth_valid[1], 1);
    EXPECT_NEAR(scan->azimuth_angles_rad[1], 23.0 / 5600 * 2 * std::numbers::pi, 1e-12);
    EXPECT_EQ(scan->row(7)[11], test::syntheticPower(7, 11));
  }
  // global_pose.csv (base poses at 10 Hz, driving 10 m/s along the base x) is interpolated to
  // the scans' mid-sweep reference times: relative to the first GT row's time t_a, the radar has
  // moved 10 m/s * (t - t_a) along its x, rotated by the -0.9 deg mounting yaw.
  std::string csv;
  const StampNs t_a = kT0 - 100'000'000LL;
  for (int k = 0; k < 15; ++k) {
    char line[256];
    std::snprintf(line, sizeof line, "%lld,1,0,0,%.3f,0,1,0,4000000,0,0,1,20\n",
                  static_cast<long long>(t_a + k * 100'000'000LL), 350000.0 + k * 1.0);
    csv += line;
  }
  test::writeText(tmp / "global_pose.csv", csv);
  const auto with_gt = openDataset(tmp.path());
  ASSERT_TRUE(with_gt->hasGroundTruth());
  for (std::size_t s = 0; s < 3; ++s) {
    const auto scan = with_gt->readScan(s);
    const auto pose = with_gt->groundTruthAt(scan->refStampNs());
    ASSERT_TRUE(pose.has_value());
    const double d = 10.0 * toSeconds(scan->refStampNs() - t_a);
    const double a = -0.9 * std::numbers::pi / 180;
    EXPECT_NEAR(pose->x, d * std::cos(a), 1e-6);
    EXPECT_NEAR(pose->y, d * std::sin(a), 1e-6);
    EXPECT_NEAR(pose->phi, 0.0, 1e-9);
  }
  // readScanFile finds the scan through its dataset folder.
  const auto single = readScanFile(reader->scanPath(1));
  EXPECT_EQ(single->azimuth_stamps_ns.back(), lastAzimuth(1));
}

TEST(MulRanReader, PlainPolarIsTransposedInFiringOrder) {
  test::TempDir tmp;
  for (int s = 0; s < 3; ++s)
    test::writeTransposedPng(
        tmp / "sensor_data" / "radar" / "polar" / (std::to_string(lastAzimuth(s)) + ".png"), kAz, kBins);
  const auto reader = openDataset(tmp.path());
  EXPECT_EQ(reader->kind(), DatasetKind::MulRanPolar);
  ASSERT_EQ(reader->size(), 3u);
  const auto scan = reader->readScan(1);
  ASSERT_EQ(scan->num_azimuths, static_cast<std::uint32_t>(kAz));
  ASSERT_EQ(scan->num_bins, static_cast<std::uint32_t>(kBins));
  // Column j of the image is azimuth j (firing order), angle 2*pi*j/N.
  for (int a = 0; a < kAz; ++a)
    for (int b = 0; b < kBins; b += 7)
      ASSERT_EQ(scan->row(a)[b], test::syntheticPower(a, b)) << a << "," << b;
  EXPECT_NEAR(scan->azimuth_angles_rad[10], 2 * std::numbers::pi * 10 / kAz, 1e-12);
  // End-stamped: the last azimuth is at the file's time; azimuths evenly over one frame interval.
  EXPECT_EQ(scan->azimuth_stamps_ns.back(), lastAzimuth(1));
  EXPECT_NEAR(static_cast<double>(scan->azimuth_stamps_ns[1] - scan->azimuth_stamps_ns[0]), kAzStep, 1.0);
  EXPECT_EQ(scan->checkConsistency(), "");
}

TEST(MulRanGroundTruth, BasePosesBecomeRadarPosesRelativeToTheFirst) {
  test::TempDir tmp;
  // Vehicle heading 30 deg, driving 10 m/s along its x, turning at 0.1 rad/s; 10 Hz rows.
  std::string csv;
  double x = 350000.0, y = 4000000.0, yaw = 30 * std::numbers::pi / 180;
  for (int k = 0; k < 50; ++k) {
    const StampNs t = kT0 - 1'000'000'000LL + k * 100'000'000LL;
    const double c = std::cos(yaw), s = std::sin(yaw);
    char line[512];
    std::snprintf(line, sizeof line, "%lld,%.15g,%.15g,0,%.15g,%.15g,%.15g,0,%.15g,0,0,1,20.5\n",
                  static_cast<long long>(t), c, -s, x, s, c, y);
    csv += line;
    x += c * 1.0;
    y += s * 1.0;
    yaw += 0.01;
  }
  test::writeText(tmp / "global_pose.csv", csv);
  const auto gt = readMulRanGroundTruth(tmp / "global_pose.csv");
  ASSERT_EQ(gt.size(), 50u);
  EXPECT_NEAR(gt[0].pose.x, 0.0, 1e-6);
  EXPECT_NEAR(gt[0].pose.phi, 0.0, 1e-9);
  // One step later the radar (1.5 m ahead of the base, mounted at +0.9 deg yaw) has turned by
  // 0.01 rad, and the base moved 1 m along its x: in the first radar frame that is
  // R(-0.9 deg) * (1 + 1.5 (cos 0.01 - 1) + 0.04 sin 0.01, 1.5 sin 0.01 - 0.04 (cos 0.01 - 1)).
  const double a = -0.9 * std::numbers::pi / 180;
  const double dx = 1 + 1.5 * (std::cos(0.01) - 1) + 0.04 * std::sin(0.01);
  const double dy = 1.5 * std::sin(0.01) - 0.04 * (std::cos(0.01) - 1);
  EXPECT_NEAR(gt[1].pose.x, std::cos(a) * dx - std::sin(a) * dy, 1e-6);
  EXPECT_NEAR(gt[1].pose.y, std::sin(a) * dx + std::cos(a) * dy, 1e-6);
  EXPECT_NEAR(gt[1].pose.phi, 0.01, 1e-9);
  EXPECT_NEAR(gt[49].pose.phi, 0.49, 1e-9);

  test::writeText(tmp / "bad.csv", "1564718975911638410,1,0,0\n");
  test::expectInputError([&] { readMulRanGroundTruth(tmp / "bad.csv"); }, "bad.csv:1", "expected 13");
}

// The real scan in the plain polar layout, in a folder with nothing else (no global_pose.csv,
// no data_stamp.csv): it reads as the CSV does, without ground truth or missing-part notes.
TEST(MulRanReader, PlainPolarFolderWithoutSideFilesReadsTheRealScan) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "mulran_single_ray_scan");
  const auto csv = readScanFile(dir / "1564718976161407002.csv");
  test::TempDir tmp;
  cv::Mat rows(static_cast<int>(csv->num_azimuths), static_cast<int>(csv->num_bins), CV_8UC1,
               const_cast<std::uint8_t*>(csv->power.data()));
  const auto png = tmp / "sensor_data" / "radar" / "polar" / "1564718976161407002.png";
  std::filesystem::create_directories(png.parent_path());
  ASSERT_TRUE(cv::imwrite(png.string(), cv::Mat(rows.t())));  // rows = bins, columns = azimuths
  const auto reader = openDataset(tmp.path());
  EXPECT_EQ(reader->kind(), DatasetKind::MulRanPolar);
  ASSERT_EQ(reader->size(), 1u);
  EXPECT_FALSE(reader->hasGroundTruth());
  EXPECT_TRUE(reader->missingParts().empty());
  const auto scan = reader->readScan(0);
  EXPECT_EQ(scan->checkConsistency(), "");
  EXPECT_EQ(scan->power, csv->power);
  EXPECT_EQ(scan->azimuth_stamps_ns.back(), csv->azimuth_stamps_ns.back());  // end-stamped
  // One scan: the sweep is the nominal 250 ms (no neighbour to measure it from).
  EXPECT_NEAR(toSeconds(scan->azimuth_stamps_ns.back() - scan->azimuth_stamps_ns.front()), 0.25 * 399 / 400,
              1e-3);
}
