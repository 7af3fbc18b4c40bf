// `radarslam map-synth` + `radarslam export` end to end (real Oxford tiny sample: a map from its
// ground truth, every export format written and non-empty, stdout = the list of files), and
// one-line errors with a non-zero exit code for a bad map path, a corrupt map and bad options.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace {

using radarslam::test::runCli;
using Result = radarslam::test::CliResult;

std::size_t lineCount(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace

TEST(CliExport, ExportsEveryFormatOfAMapBuiltFromGroundTruth) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const auto map = tmp / "oxmap";
  Result r = runCli("map-synth '" + dir.string() + "' -o '" + map.string() + "' --every 0.5", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("keyframes"), std::string::npos) << r.out;
  ASSERT_TRUE(std::filesystem::exists(map / "manifest.yaml"));

  r = runCli("export '" + map.string() + "' --resolution 0.5", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  // stdout carries exactly the written files (OctoMap's own prints must not leak into it).
  std::istringstream lines(r.out);
  std::vector<std::string> files;
  for (std::string line; std::getline(lines, line);) files.push_back(line);
  EXPECT_EQ(files.size(), 10u) << r.out;
  for (const auto& f : files) {
    ASSERT_TRUE(std::filesystem::is_regular_file(f)) << f;
    EXPECT_GT(std::filesystem::file_size(f), 0u) << f;
    EXPECT_EQ(std::filesystem::path(f).parent_path(), map / "exports") << f;
  }

  // Only the cloud, into another directory.
  r = runCli("export '" + map.string() + "' --cloud -o '" + (tmp / "out").string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(lineCount(r.out), 2u) << r.out;
  EXPECT_TRUE(std::filesystem::exists(tmp / "out" / "cloud.pcd"));
  EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "grid.png"));
}

TEST(CliExport, BadMapPathIsOneLineError) {
  radarslam::test::TempDir tmp;
  const Result r = runCli("export '" + (tmp / "no_such_map").string() + "'", tmp);
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("no_such_map"), std::string::npos) << r.err;
}

TEST(CliExport, CorruptMapIsOneLineErrorNamingTheFile) {
  radarslam::test::TempDir tmp;
  const auto map = tmp / "m";
  std::filesystem::create_directories(map);
  { std::ofstream(map / "manifest.yaml") << "format_version: 7\n"; }
  const Result r = runCli("export '" + map.string() + "'", tmp);
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("manifest.yaml"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("newer"), std::string::npos) << r.err;
}

TEST(CliExport, BadResolutionIsOneLineError) {
  radarslam::test::TempDir tmp;
  const Result r = runCli("export somewhere --resolution -1", tmp);
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("--resolution"), std::string::npos) << r.err;
}
