// `radarslam info` on a dataset as downloaded without its optional parts: it reads, and says which
// part is missing and what that disables.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "radarslam/io/dataset.h"
#include "radarslam/io/oxford_writer.h"

#include "cli_run.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

TEST(CliInfoLayouts, OxfordWithoutGroundTruthSaysWhatIsMissing) {
  RADARSLAM_REQUIRE_REAL_DATA(oxford, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const fs::path copy = tmp / "oxford";
  fs::create_directories(copy);
  fs::copy(oxford / "radar", copy / "radar", fs::copy_options::recursive);
  fs::copy_file(oxford / "radar.timestamps", copy / "radar.timestamps");
  const auto r = radarslam::test::runCli("info '" + copy.string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("scans:         11"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ground truth:  no (gt/radar_odometry.csv missing"), std::string::npos) << r.out;
}

// MulRan as polar_oxford_form/ alone (no global_pose.csv, no sensor_data/): the real scan (ray CSV)
// written in that layout reads, and info names the missing ground truth.
TEST(CliInfoLayouts, MulRanWithoutSideFilesSaysWhatIsMissing) {
  RADARSLAM_REQUIRE_REAL_DATA(mulran, "mulran_single_ray_scan");
  radarslam::test::TempDir tmp;
  const auto scan = radarslam::readScanFile(mulran / "1564718976161407002.csv");
  const auto png = radarslam::encodeOxfordPng(*scan);
  const fs::path dir = tmp / "mulran" / "polar_oxford_form";
  fs::create_directories(dir);
  std::ofstream(dir / "1564718976161407002.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  const auto r = radarslam::test::runCli("info '" + (tmp / "mulran").string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("dataset:       MulRan (polar_oxford_form)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("geometry:      400 azimuths x 3360 bins"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ground truth:  no (global_pose.csv missing"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("missing:       "), std::string::npos) << r.out;  // nothing else is needed
}

// RADIATE as Navtech_Polar/ alone (no Navtech_Polar.txt, GPS_IMU_Twist/, lidar, Cartesian images).
TEST(CliInfoLayouts, RadiateWithoutSideFilesSaysWhatIsMissing) {
  RADARSLAM_REQUIRE_REAL_DATA(radiate, "radiate_tiny_foggy");
  radarslam::test::TempDir tmp;
  fs::create_directories(tmp / "radiate");
  fs::create_directory_symlink(radiate / "Navtech_Polar", tmp / "radiate" / "Navtech_Polar");
  const auto r = radarslam::test::runCli("info --check '" + (tmp / "radiate").string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("dataset:       RADIATE"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("scans:         18"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("duration:      4.250 s"), std::string::npos) << r.out;  // 17 x nominal 250 ms
  EXPECT_NE(r.out.find("missing:       Navtech_Polar.txt missing: frames timed by their numbers"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("check:         18 good scans, 0 bad"), std::string::npos) << r.out;
  // With the frame times present, nothing is reported missing.
  const auto full = radarslam::test::runCli("info '" + radiate.string() + "'", tmp);
  ASSERT_EQ(full.code, 0) << full.err;
  EXPECT_EQ(full.out.find("missing:       "), std::string::npos) << full.out;
}

// A radar-only Boreas-RT folder (RAS6 scan, byte 10 = chirp flag, no applanix/ or calib/): read,
// the alternating chirp reported, the missing ground truth named.
TEST(CliInfoLayouts, BoreasRas6RadarOnlyReportsTheChirp) {
  radarslam::test::TempDir tmp;
  radarslam::CObservationRadarScan scan;
  scan.resize(400, 6848);
  scan.range_resolution_m = 0.04381;
  scan.range_offset_m = -0.31;
  for (std::uint32_t a = 0; a < 400; ++a) {
    scan.azimuth_stamps_ns[a] = (1733248400000000LL + a * 625LL) * 1000;
    scan.azimuth_chirp[a] = a % 2 ? -1 : 1;
    scan.row(a)[100 + a] = 200;
  }
  const auto png = radarslam::encodeOxfordPng(scan);
  const fs::path dir = tmp / "boreas-rt" / "radar";
  fs::create_directories(dir);
  std::ofstream(dir / (std::to_string(scan.azimuth_stamps_ns[199] / 1000) + ".png"), std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  const auto r = radarslam::test::runCli("info '" + (tmp / "boreas-rt").string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("dataset:       Boreas"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("sensor:        Navtech RAS6"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("geometry:      400 azimuths x 6848 bins, 0.04381 m/bin"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("chirp:         200 up / 200 down-chirp azimuths"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ground truth:  no (applanix/radar_poses.csv missing"), std::string::npos) << r.out;
}
