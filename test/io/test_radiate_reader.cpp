// RADIATE: the 18 real foggy scans.
#include <gtest/gtest.h>

#include <numbers>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;

TEST(RadiateReader, RealFogScansDecodeTransposedWithSynthesizedTimes) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "radiate_tiny_foggy");
  const auto reader = openDataset(dir);
  EXPECT_EQ(reader->kind(), DatasetKind::Radiate);
  ASSERT_EQ(reader->size(), 18u);
  EXPECT_FALSE(reader->hasGroundTruth());
  EXPECT_EQ(reader->indexStamp(0), 1574859771744660272LL);
  StampNs prev_last = 0;
  for (std::size_t i = 0; i < reader->size(); ++i) {
    SCOPED_TRACE(i);
    const auto scan = reader->readScan(i);
    EXPECT_EQ(scan->checkConsistency(), "");
    EXPECT_EQ(scan->num_bins, 576u);
    EXPECT_EQ(scan->num_azimuths, 400u);
    EXPECT_DOUBLE_EQ(scan->range_resolution_m, 0.173611);
    // The frame time is taken as mid-sweep: the reference time is exactly the frame time.
    EXPECT_EQ(scan->refStampNs(), reader->indexStamp(i));
    const double sweep_ms = toSeconds(scan->azimuth_stamps_ns.back() - scan->azimuth_stamps_ns.front()) * 1e3;
    EXPECT_GT(sweep_ms, 200.0);
    EXPECT_LT(sweep_ms, 260.0);
    // RADIATE's frame times jitter by ~10 ms around 4 Hz, so with one common sweep duration
    // consecutive sweeps may overlap slightly, but never by more than the jitter.
    if (i > 0) {
      EXPECT_GT(scan->refStampNs(), reader->indexStamp(i - 1));
      EXPECT_GT(toSeconds(scan->azimuth_stamps_ns.front() - prev_last), -0.025);
    }
    prev_last = scan->azimuth_stamps_ns.back();
    EXPECT_NEAR(scan->azimuth_angles_rad[100], std::numbers::pi / 2, 1e-12);
  }
  // Pixel (row = bin, col = azimuth) of the PNG is power(azimuth, bin).
  const cv::Mat img = cv::imread(reader->scanPath(5).string(), cv::IMREAD_UNCHANGED);
  const auto scan = reader->readScan(5);
  ASSERT_EQ(img.rows, 576);
  for (int a = 0; a < 400; a += 37)
    for (int b = 0; b < 576; b += 41) ASSERT_EQ(scan->row(a)[b], img.at<std::uint8_t>(b, a));
  EXPECT_EQ(readScanFile(reader->scanPath(5))->power, scan->power);
}

// Navtech_Polar/ alone (a copy without Navtech_Polar.txt or any other side file): the same scans,
// timed by frame number at the nominal 4 Hz; the reader says what is missing.
TEST(RadiateReader, WithoutFrameTimesFramesAreTimedByNumber) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "radiate_tiny_foggy");
  test::TempDir tmp;
  std::filesystem::create_directory_symlink(dir / "Navtech_Polar", tmp / "Navtech_Polar");
  const auto reader = openDataset(tmp.path());
  const auto full = openDataset(dir);
  EXPECT_EQ(reader->kind(), DatasetKind::Radiate);
  ASSERT_EQ(reader->size(), 18u);
  EXPECT_TRUE(full->missingParts().empty());
  ASSERT_EQ(reader->missingParts().size(), 1u);
  EXPECT_NE(reader->missingParts()[0].find("Navtech_Polar.txt missing"), std::string::npos);
  EXPECT_EQ(reader->indexStamp(0), 946684800LL * kNsPerSec);  // frame 1 at 2000-01-01
  for (std::size_t i = 0; i < reader->size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(reader->scanPath(i).filename(), full->scanPath(i).filename());
    if (i > 0) {
      EXPECT_EQ(reader->indexStamp(i) - reader->indexStamp(i - 1), 250'000'000);
    }
  }
  const auto scan = reader->readScan(7);
  EXPECT_EQ(scan->checkConsistency(), "");
  EXPECT_EQ(scan->power, full->readScan(7)->power);
  EXPECT_EQ(scan->refStampNs(), reader->indexStamp(7));
  EXPECT_NEAR(toSeconds(scan->azimuth_stamps_ns.back() - scan->azimuth_stamps_ns.front()), 0.25 * 399 / 400,
              1e-6);
}

TEST(RadiateReader, WithoutFrameTimesFileNamesMustBeFrameNumbers) {
  test::TempDir tmp;
  test::writeTransposedPng(tmp / "Navtech_Polar" / "000001.png", 40, 30);
  test::writeTransposedPng(tmp / "Navtech_Polar" / "frame2.png", 40, 30);
  test::expectInputError([&] { openDataset(tmp.path()); }, "frame2.png", "not a frame number");
}
