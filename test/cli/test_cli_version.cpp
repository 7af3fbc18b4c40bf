// `--version` of every subcommand names the version and the git revision it was built from, and
// a saved map records the same text in its manifest (software_version).
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "cli_run.h"
#include "file_contents.h"
#include "radarslam/core/version.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;

TEST(CliVersion, EveryCommandPrintsVersionAndGitRevision) {
  const std::regex rev(R"(\d+\.\d+\.\d+ \(git ([0-9a-f]{12}(-dirty)?|unknown)\))");
  test::TempDir tmp;
  for (const std::string cmd : {"--version", "odometry --version", "map --version", "localize --version"}) {
    const auto r = test::runCli(cmd, tmp);
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_TRUE(std::regex_search(r.out, rev)) << cmd << ": " << r.out;
    EXPECT_NE(r.out.find(versionText()), std::string::npos) << cmd << ": " << r.out;
  }
}

TEST(CliVersion, MapManifestRecordsTheVersion) {
  RADARSLAM_REQUIRE_REAL_DATA(oxford, "oxford_radar_robotcar_tiny");
  test::TempDir tmp;
  const auto map = tmp / "m";
  const auto r = test::runCli("map-synth '" + oxford.string() + "' -o '" + map.string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string manifest = test::readFileBytes(map / "manifest.yaml");
  EXPECT_NE(manifest.find(versionText()), std::string::npos) << manifest;
}
