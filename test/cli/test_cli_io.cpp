// `radarslam info` and `radarslam convert` end to end: what info reports for the real Oxford
// tiny sample, conversion to a rawlog and back, --skip-bad-scans, and one-line errors with a
// non-zero exit code for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_run.h"
#include "radarslam/io/dataset.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace {

using CliRun = radarslam::test::CliResult;
using radarslam::test::runCli;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(CliInfo, ReportsTheOxfordTinySample) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const CliRun r = runCli("info '" + dir.string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "dataset:       Oxford Radar RobotCar")) << r.out;
  EXPECT_TRUE(contains(r.out, "scans:         11\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "400 azimuths x 3768 bins, 0.0432 m/bin")) << r.out;
  EXPECT_TRUE(contains(r.out, "max range 162.8 m")) << r.out;
  EXPECT_TRUE(contains(r.out, "ground truth:  yes")) << r.out;
  EXPECT_TRUE(contains(r.out, "duration:      2.492 s")) << r.out;
  EXPECT_TRUE(contains(r.out, "sensor:        Navtech CTS350-X")) << r.out;
}

TEST(CliInfo, HelpAndErrors) {
  radarslam::test::TempDir tmp;
  for (const char* cmd : {"info --help", "convert --help"}) {
    const CliRun r = runCli(cmd, tmp);
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_TRUE(contains(r.out, "USAGE")) << r.out;
  }
  const CliRun empty = runCli("info '" + tmp.path().string() + "'", tmp);  // holds only our capture files
  EXPECT_EQ(empty.code, 1);
  EXPECT_TRUE(contains(empty.err, "unknown dataset layout")) << empty.err;
  std::filesystem::create_directories(tmp / "empty");
  const CliRun r = runCli("info '" + (tmp / "empty").string() + "'", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "radarslam: error: " + (tmp / "empty").string() + ": empty directory"))
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const CliRun bad_opt = runCli("info --bogus x", tmp);
  EXPECT_NE(bad_opt.code, 0);
}

TEST(CliConvert, OxfordToRawlogAndBack) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const auto out = tmp / "tiny.rawlog";
  const CliRun r = runCli("convert '" + dir.string() + "' '" + out.string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "scans/s")) << r.err;
  EXPECT_TRUE(contains(r.err, "ETA")) << r.err;
  EXPECT_TRUE(contains(r.out, "converted 11 scans")) << r.out;
  EXPECT_TRUE(contains(r.out, "skipped 0 bad scan(s)")) << r.out;
  const CliRun info = runCli("info '" + out.string() + "'", tmp);
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_TRUE(contains(info.out, "dataset:       MRPT rawlog")) << info.out;
  EXPECT_TRUE(contains(info.out, "scans:         11\n")) << info.out;
  EXPECT_TRUE(contains(info.out, "400 azimuths x 3768 bins, 0.0432 m/bin")) << info.out;
  // The library reads what the program wrote, scan for scan.
  const auto a = radarslam::openDataset(dir), b = radarslam::openDataset(out);
  ASSERT_EQ(b->size(), 11u);
  EXPECT_EQ(a->readScan(10)->power, b->readScan(10)->power);
}

TEST(CliConvert, BadScanFailsUnlessSkipped) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const auto copy = tmp / "oxford";
  std::filesystem::create_directories(copy / "radar");
  std::filesystem::copy_file(dir / "radar.timestamps", copy / "radar.timestamps");
  for (const auto& e : std::filesystem::directory_iterator(dir / "radar"))
    std::filesystem::copy_file(e.path(), copy / "radar" / e.path().filename());
  const auto bad = copy / "radar" / "1547131047356527.png";  // scan 4
  std::filesystem::permissions(bad, std::filesystem::perms::owner_write, std::filesystem::perm_options::add);
  std::filesystem::resize_file(bad, 5000);
  const auto out = tmp / "o.rawlog";

  const CliRun strict = runCli("convert '" + copy.string() + "' '" + out.string() + "'", tmp);
  EXPECT_EQ(strict.code, 1);
  EXPECT_TRUE(contains(strict.err, "radarslam: error: " + bad.string() + ": truncated PNG")) << strict.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "a failed conversion must not leave an output file";

  const CliRun lenient =
      runCli("convert --skip-bad-scans '" + copy.string() + "' '" + out.string() + "'", tmp);
  ASSERT_EQ(lenient.code, 0) << lenient.err;
  EXPECT_TRUE(contains(lenient.out, "converted 10 scans")) << lenient.out;
  EXPECT_TRUE(contains(lenient.out, "skipped 1 bad scan(s)")) << lenient.out;
  // The warning goes through the MRPT logger (which prints to stdout or stderr by level).
  EXPECT_TRUE(contains(lenient.out + lenient.err, "skipping bad scan 4")) << lenient.out << lenient.err;
  EXPECT_EQ(radarslam::openDataset(out)->size(), 10u);

  const CliRun check = runCli("info --check --skip-bad-scans '" + copy.string() + "'", tmp);
  ASSERT_EQ(check.code, 0) << check.err;
  EXPECT_TRUE(contains(check.out, "check:         10 good scans, 1 bad (skipped)")) << check.out;
  const CliRun wrong_ext = runCli("convert '" + copy.string() + "' '" + (tmp / "x.txt").string() + "'", tmp);
  EXPECT_EQ(wrong_ext.code, 1);
  EXPECT_TRUE(contains(wrong_ext.err, "output must be a .rawlog file")) << wrong_ext.err;
}
