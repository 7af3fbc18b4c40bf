// SLAM parameters: every shipped config loads as a whole (front end + slam:) with no unknown key,
// the shipped values are what the file says, and bad values are one-line errors naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/slam/slam_params.h"

namespace radarslam {
namespace {

TEST(SlamParams, EveryShippedConfigLoadsWithNoUnknownKey) {
  for (const char* name : {"oxford", "mulran", "boreas", "radiate", "sim_radar"}) {
    const auto path = std::filesystem::path(RADARSLAM_SOURCE_DIR) / "config" / (std::string(name) + ".yaml");
    SCOPED_TRACE(path.string());
    const YamlParams y = YamlParams::fromFile(path.string());
    SlamParams p;
    EXPECT_NO_THROW(loadParams(y, p));
    EXPECT_NO_THROW(y.rejectUnknownKeys());
  }
}

TEST(SlamParams, OverridesAndDefaults) {
  const YamlParams y = YamlParams::fromText(
      "slam:\n  threads: 1\n  local_mapping:\n    window_keyframes: 8\n  loop_closure:\n    drift_fraction: "
      "0\n"
      "    verifier:\n      min_inliers: 55\n",
      "t.yaml");
  SlamParams p;
  loadParams(y, p);
  y.rejectUnknownKeys();
  EXPECT_EQ(p.threads, 1);
  EXPECT_EQ(p.local_mapping.window_keyframes, 8);
  EXPECT_EQ(p.loop_closing.drift_fraction, 0.0);
  EXPECT_EQ(p.loop_closing.verifier.min_inliers, 55u);
  EXPECT_EQ(p.local_mapping.interval_keyframes, SlamParams{}.local_mapping.interval_keyframes);
}

TEST(SlamParams, BadValuesAndTyposAreErrorsNamingTheFile) {
  const auto expectError = [](const std::string& text, const std::string& needle) {
    try {
      const YamlParams y = YamlParams::fromText(text, "bad.yaml");
      SlamParams p;
      loadParams(y, p);
      y.rejectUnknownKeys();
      ADD_FAILURE() << "no error for: " << text;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad.yaml"), std::string::npos) << what;
      EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
  };
  expectError("slam:\n  threads: 0\n", "threads");
  expectError("slam:\n  local_mapping:\n    window_keyframes: 1\n", "window_keyframes");
  expectError("slam:\n  local_mapping:\n    interval_keyframes: 9\n", "interval_keyframes");
  expectError("slam:\n  loop_closure:\n    max_verifications: 0\n", "max_verifications");
  expectError("slam:\n  odometry_edges:\n    lost_factor: 0.5\n", "lost_factor");
  expectError("slam:\n  loop_closure:\n    confirm_ambiguous_keyframes: 1\n", "confirm_ambiguous_keyframes");
  expectError("slam:\n  loop_closure:\n    confirm_max_gap_keyframes: 0\n", "confirm_max_gap_keyframes");
  expectError("slam:\n  local_mapping:\n    windw_keyframes: 4\n", "windw_keyframes");
}

}  // namespace
}  // namespace radarslam
