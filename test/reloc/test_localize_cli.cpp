// Integration: a small simulated world, a map from the first traversal (map-synth, ground truth),
// `radarslam localize` on the second traversal (other lane, other parked cars and traffic).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "file_contents.h"
#include "simulated_dataset.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

using radarslam::test::readFileBytes;

int run(const std::string& args, const std::filesystem::path& log) {
  const std::string cmd = std::string(RADARSLAM_CLI) + " " + args + " > '" + log.string() + "' 2>&1";
  return std::system(cmd.c_str());
}

/// Data rows (not starting with '#') of a whitespace-separated file.
std::vector<std::vector<std::string>> rows(const std::filesystem::path& p) {
  std::vector<std::vector<std::string>> out;
  std::ifstream f(p);
  for (std::string line; std::getline(f, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> cols;
    for (std::string c; ss >> c;) cols.push_back(c);
    out.push_back(cols);
  }
  return out;
}

// The drives of test_localize_integrity.cpp (simulated once for all): traversals 1 and 2.
constexpr std::size_t kScans = 130;
std::filesystem::path traversal(int k) {
  return test::simulatedDataset("--scans " + std::to_string(kScans) + (k == 2 ? " --traversal 2" : ""));
}

TEST(LocalizeCli, SecondTraversalOfSimulatedWorld) {
  test::TempDir tmp;
  const auto d = tmp.path();
  const std::filesystem::path t1 = traversal(1), t2 = traversal(2);
  ASSERT_EQ(run("map-synth '" + t1.string() + "' -o '" + (d / "map").string() + "'", d / "synth.log"), 0)
      << readFileBytes(d / "synth.log");
  const auto poses = d / "poses.tum";
  ASSERT_EQ(run("localize '" + (d / "map").string() + "' '" + t2.string() + "' -o '" + poses.string() +
                    "' --eval-dir '" + (d / "eval").string() + "' -q",
                d / "loc.log"),
            0)
      << readFileBytes(d / "loc.log");
  const std::string log = readFileBytes(d / "loc.log");

  // Per-scan side file: one row per scan, status and localised flag consistent.
  const auto side = rows(poses.string() + ".csv");
  ASSERT_EQ(side.size(), kScans) << log;
  std::size_t localised = 0;
  for (const auto& r : side) {
    ASSERT_EQ(r.size(), 28u);
    localised += r[3] == "1";
    EXPECT_EQ(r[3] == "1", r[2] != "lost");
  }
  EXPECT_GE(localised, kScans * 9 / 10) << log;
  EXPECT_EQ(rows(poses).size(), localised);
  // Boreas localisation rows: stamps, 3x4 T_keyframe_scan, 6x6 inverse covariance; one per pose.
  const auto boreas = rows(poses.string() + ".boreas.txt");
  ASSERT_EQ(boreas.size(), localised);
  for (const auto& r : boreas) {
    ASSERT_EQ(r.size(), 50u);
    EXPECT_GT(std::stod(r[14]), 0);              // information of x
    EXPECT_EQ(std::stod(r[14 + 2 * 6 + 2]), 0);  // no information on z
  }
  // eval --localization against the truth in the map frame.
  ASSERT_EQ(run("eval --localization '" + poses.string() + ".csv' '" +
                    (d / "eval" / "truth_map.tum").string() + "' --json '" + (d / "loc.json").string() + "'",
                d / "evalloc.log"),
            0)
      << readFileBytes(d / "evalloc.log");
  const std::string json = readFileBytes(d / "loc.json");
  EXPECT_NE(json.find("\"nees_mean\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"trusted_far_off\": 0,"), std::string::npos) << json;
  EXPECT_NE(readFileBytes(d / "evalloc.log").find("RMSE"), std::string::npos);
  // The first fix comes within the first 3 scans.
  EXPECT_TRUE(side[0][3] == "1" || side[1][3] == "1" || side[2][3] == "1") << log;

  // Errors against the absolute simulator truth.
  const auto errors = rows(d / "eval" / "errors.csv");
  ASSERT_EQ(errors.size(), localised) << log;
  std::vector<double> pos, head;
  for (const auto& r : errors) {
    ASSERT_EQ(r.size(), 11u);
    pos.push_back(std::stod(r[3]));
    head.push_back(std::stod(r[4]));
    // A map-synth map has no error of its own: relative to the map = absolute.
    EXPECT_NEAR(std::stod(r[9]), std::stod(r[3]), 2e-3) << r[0];
  }
  std::sort(pos.begin(), pos.end());
  std::sort(head.begin(), head.end());
  EXPECT_LT(pos[pos.size() / 2], 0.5) << log;
  EXPECT_LT(head[head.size() / 2], 1.0) << log;
  EXPECT_LT(pos.back(), 5.0) << log;  // nothing reported as localised is far off
  EXPECT_NE(log.find("absolute gt/poses.tum"), std::string::npos) << log;
  EXPECT_NE(
      log.find("model error    0.000 m, 0.250 deg added to each registration's covariance (a map of raw"),
      std::string::npos)
      << log;
  // The map frame is fitted to the truth at the map's keyframes: exact for a map-synth map.
  const auto fit = log.find("residual RMS ");
  ASSERT_NE(fit, std::string::npos) << log;
  EXPECT_LT(std::stod(log.substr(fit + 13)), 0.01) << log;
}

// In a map `radarslam map` built (motion-compensated clouds, manifest clouds_motion_compensated:
// true) the localiser uses the clouds as stored. Compensating them again, as config/localization.yaml's
// map_sweep_period_s did for every map, shifted each point by twice its motion during the sweep:
// on this drive 65 % of the scans within 0.3 m / 0.5 deg of the map instead of 97 %.
TEST(LocalizeCli, InASlamMapTheCompensatedCloudsAreUsedAsStored) {
  test::TempDir tmp;
  const auto d = tmp.path();
  const std::filesystem::path t1 = traversal(1), t2 = traversal(2);
  ASSERT_EQ(run("map '" + t1.string() + "' -o '" + (d / "map").string() + "' --threads 1 -q", d / "map.log"),
            0)
      << readFileBytes(d / "map.log");
  ASSERT_NE(readFileBytes(d / "map" / "manifest.yaml").find("clouds_motion_compensated: true"),
            std::string::npos);
  ASSERT_EQ(run("localize '" + (d / "map").string() + "' '" + t2.string() + "' -o '" +
                    (d / "p.tum").string() + "' --eval-dir '" + (d / "eval").string() + "' -q",
                d / "loc.log"),
            0)
      << readFileBytes(d / "loc.log");
  // errors.csv: stamp scan status ... position and heading error relative to the nearest map keyframe.
  std::size_t good = 0;
  for (const auto& r : rows(d / "eval" / "errors.csv")) {
    ASSERT_EQ(r.size(), 11u);
    good += r[2] == "tracking" && std::stod(r[9]) <= 0.3 && std::stod(r[10]) <= 0.5;
  }
  // Issue 14's target is 95 % of the scans; measured 125 of 130 (double compensation: 84).
  EXPECT_GE(good, kScans * 9 / 10) << readFileBytes(d / "loc.log");
  // The summary says which model errors the covariance got: a SLAM map's.
  EXPECT_NE(
      readFileBytes(d / "loc.log")
          .find("model error    0.035 m, 0.140 deg added to each registration's covariance (a SLAM map"),
      std::string::npos)
      << readFileBytes(d / "loc.log");
}

TEST(LocalizeCli, MissingMapIsOneLineError) {
  test::TempDir tmp;
  const auto d = tmp.path();
  EXPECT_NE(run("localize '" + (d / "nomap").string() + "' '" + d.string() + "' -o '" +
                    (d / "p.tum").string() + "'",
                d / "err.log"),
            0);
  const std::string err = readFileBytes(d / "err.log");
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

}  // namespace
}  // namespace radarslam
