// `radarslam eval`: runs the built program on generated trajectory files and checks exit codes, the
// printed summary, the JSON report and the plots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "file_contents.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/trajectory_files.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;
using mrpt::math::TPose2D;
namespace fs = std::filesystem;

namespace {

using radarslam::test::readFileBytes;

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

/// Runs `radarslam eval <args>` with stdout and stderr captured in files next to `dir`.
CliRun runEval(const test::TempDir& dir, const std::string& args) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd =
      std::string(RADARSLAM_CLI) + " eval " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readFileBytes(out);
  r.err = readFileBytes(err);
  return r;
}

/// A 1.2 km drive along +x at 4 Hz, stamps in 2019. Poses are 1 m + 10 um apart so that every KITTI
/// segment ends at its nominal length (see test_kitti_metric) and TUM's 6 decimals keep them exact.
Trajectory groundTruth() {
  Trajectory t;
  for (int k = 0; k < 1200; ++k)
    t.push_back({1547120788016733000LL + k * 250'000'000LL, TPose2D(k * 1.00001, 0, 0)});
  return t;
}

Trajectory scaled(Trajectory t, double s) {
  for (auto& p : t) p.pose.x *= s, p.pose.y *= s;
  return t;
}

std::size_t lineCount(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TEST(CliEval, ScoresAOnePercentScaleErrorAndWritesReportAndPlots) {
  test::TempDir dir;
  writeTumTrajectory(dir / "gt.txt", groundTruth());
  writeTumTrajectory(dir / "est.txt", scaled(groundTruth(), 1.01));
  const CliRun r =
      runEval(dir, (dir / "est.txt").string() + " " + (dir / "gt.txt").string() + " --json " +
                       (dir / "out/report.json").string() + " --plot-dir " + (dir / "plots").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("translation 1.000 %"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1200 estimated, 1200 matched"), std::string::npos) << r.out;
  const std::string json = readFileBytes(dir / "out/report.json");
  EXPECT_NE(json.find("\"t_err_percent\": 1.0000"), std::string::npos) << json.substr(0, 2000);
  for (const char* f : {"trajectory.svg", "trajectory.png", "segment_errors.svg", "segment_errors.png"})
    EXPECT_GT(fs::file_size(dir / "plots" / f), 1000u) << f;
}

TEST(CliEval, ReadsKittiEstimatesWithTheirStampsAndReportsDroppedPoses) {
  test::TempDir dir;
  writeTumTrajectory(dir / "gt.txt", groundTruth());
  Trajectory est = groundTruth();
  for (auto& p : est) p.stamp += 10 * kNsPerSec;  // the last 40 estimates lie beyond the ground truth
  writeKittiTrajectory(dir / "est.kitti", est);
  const CliRun r =
      runEval(dir, (dir / "est.kitti").string() + " " + (dir / "gt.txt").string() + " --est-format kitti");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1160 matched"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 before, 40 after"), std::string::npos) << r.out;
}

TEST(CliEval, HelpExitsZeroAndListsTheOptions) {
  test::TempDir dir;
  const CliRun r = runEval(dir, "--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--json", "--plot-dir", "--est-format", "--gt-format", "--step"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(CliEval, BadInputGivesOneLineAndAFailingExitCode) {
  test::TempDir dir;
  writeTumTrajectory(dir / "gt.txt", groundTruth());
  std::ofstream(dir / "bad.txt") << "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1\n";
  const std::string gt = (dir / "gt.txt").string();
  const std::vector<std::pair<std::string, std::string>> cases{
      {(dir / "bad.txt").string() + " " + gt, (dir / "bad.txt").string() + ":2"},
      {(dir / "missing.txt").string() + " " + gt, "not found"},
      {gt + " " + gt + " --est-format csv", "unknown trajectory format"},
      {gt + " " + gt + " --step 0", "--step"},
      {gt + " " + gt + " --no-such-option", "radarslam eval"},
      {gt, "radarslam eval"},
  };
  for (const auto& [args, words] : cases) {
    const CliRun r = runEval(dir, args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << args << "\n" << r.err;
  }
  // Estimates that never overlap the ground truth in time.
  Trajectory late = groundTruth();
  for (auto& p : late) p.stamp += 3600 * kNsPerSec;
  writeTumTrajectory(dir / "late.txt", late);
  const CliRun r = runEval(dir, (dir / "late.txt").string() + " " + gt);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("time span"), std::string::npos) << r.err;
}

TEST(CliEval, TakesGroundTruthFromADatasetDirectory) {
  RADARSLAM_REQUIRE_REAL_DATA(oxford, "oxford_radar_robotcar_2019-01-10-11-46-21");
  test::TempDir dir;
  // The dataset's own ground truth, 1 % too long, as the estimate.
  writeTumTrajectory(dir / "est.txt", scaled(openDataset(oxford)->groundTruth(), 1.01));
  const CliRun r = runEval(dir, (dir / "est.txt").string() + " " + oxford.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("8866 estimated, 8866 matched"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.000 deg/100m"), std::string::npos) << r.out;    // a pure scale error
  EXPECT_NE(r.out.find("translation 0.71"), std::string::npos) << r.out;  // see test_oxford_ground_truth

  const CliRun est_dir = runEval(dir, oxford.string() + " " + oxford.string());
  EXPECT_NE(est_dir.exit_code, 0);
  EXPECT_NE(est_dir.err.find("not a directory"), std::string::npos) << est_dir.err;
}
