// `radarslam odometry` end to end on the real Oxford tiny sample: TUM output, --first/--count,
// evaluation against the dataset's ground truth (--eval-dir), and one-line errors.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_run.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/trajectory_files.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace {

using Result = radarslam::test::CliResult;

Result runOdometry(const std::string& args, const radarslam::test::TempDir& tmp) {
  return radarslam::test::runCli("odometry " + args, tmp);
}

TEST(CliOdometry, TracksOxfordAndEvaluatesAgainstGroundTruth) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const auto traj = tmp / "traj.tum";
  const auto eval = tmp / "eval";
  const Result r = runOdometry(
      "'" + dir.string() + "' -o '" + traj.string() + "' --eval-dir '" + eval.string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  const radarslam::Trajectory t = radarslam::readTumTrajectory(traj);
  ASSERT_EQ(t.size(), 11u);
  EXPECT_EQ(t.front().pose.x, 0.0);
  // The end point agrees with the ground truth's (19.4 m path) to a few decimetres.
  const auto reader = radarslam::openDataset(dir);
  const auto g0 = reader->groundTruthAt(t.front().stamp), g1 = reader->groundTruthAt(t.back().stamp);
  ASSERT_TRUE(g0 && g1);
  const auto g = *g1 - *g0;
  EXPECT_GT(g.x, 19.0);
  EXPECT_LT(std::hypot(t.back().pose.x - g.x, t.back().pose.y - g.y), 0.4);
  EXPECT_NE(r.out.find("11 tracked, 0 lost"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("RPE per frame"), std::string::npos) << r.out;  // the evaluation toolkit's summary
  EXPECT_TRUE(std::filesystem::exists(eval / "report.json"));
  EXPECT_NE(r.err.find("scans/s"), std::string::npos) << r.err;      // progress with rate
  EXPECT_NE(r.err.find("oxford.yaml"), std::string::npos) << r.err;  // default config by dataset kind
}

TEST(CliOdometry, FirstAndCountSelectScans) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const auto traj = tmp / "part.tum";
  const Result r =
      runOdometry("'" + dir.string() + "' -o '" + traj.string() + "' --first 4 --count 5 -q", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  const radarslam::Trajectory t = radarslam::readTumTrajectory(traj);
  ASSERT_EQ(t.size(), 5u);
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double step = std::hypot(t[i].pose.x - t[i - 1].pose.x, t[i].pose.y - t[i - 1].pose.y);
    EXPECT_GT(step, 1.4);  // the vehicle moves 1.6-2.1 m per scan here
    EXPECT_LT(step, 2.3);
  }
}

TEST(CliOdometry, BadInputIsAOneLineError) {
  radarslam::test::TempDir tmp;
  const auto traj = tmp / "t.tum";
  Result r = runOdometry("'" + (tmp / "missing").string() + "' -o '" + traj.string() + "'", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing"), std::string::npos);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(traj));

  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  const auto cfg = tmp / "bad.yaml";
  std::ofstream(cfg) << "odometry:\n  keyframes:\n    max_translaton_m: 2\n";
  r = runOdometry("'" + dir.string() + "' -o '" + traj.string() + "' --config '" + cfg.string() + "'", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("max_translaton_m"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad.yaml"), std::string::npos) << r.err;
  r = runOdometry("'" + dir.string() + "' -o '" + traj.string() + "' --count 0", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--count"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(traj));
}

}  // namespace
