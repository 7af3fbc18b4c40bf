// `radarslam info` on a dataset as downloaded without its optional parts: it reads, and says which
// part is missing and what that disables.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

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
