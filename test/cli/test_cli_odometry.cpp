// `radarslam odometry` end to end on the real Oxford tiny sample: TUM output, --first/--count,
// evaluation against the dataset's ground truth (--eval-dir), and one-line errors.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "radarslam/frontend/pose_refiner.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/trajectory_files.h"
#include "shared_data.h"
#include "simulated_dataset.h"
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

std::vector<std::vector<std::string>> readCsv(const std::filesystem::path& file) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    rows.push_back(fields);
  }
  return rows;
}

TEST(CliOdometry, StepsRecordEveryScanItsPredictionAndTheTruth) {
  namespace fs = std::filesystem;
  const fs::path data = radarslam::test::simulatedDataset("--scans 40");
  radarslam::test::TempDir tmp;
  const auto traj = tmp / "t.tum", steps = tmp / "steps.csv";
  const Result r = runOdometry(
      "'" + data.string() + "' -o '" + traj.string() + "' --steps '" + steps.string() + "' -q", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = readCsv(steps);
  ASSERT_EQ(rows.size(), 41u);  // header + one row per scan
  const std::vector<std::string>& header = rows[0];
  ASSERT_EQ(header.size(), 25u);
  auto column = [&header](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t status = column("status"), radius = column("radius_m"), pdx = column("pred_dx_m"),
                    pdy = column("pred_dy_m"), edx = column("est_dx_m"), edy = column("est_dy_m"),
                    tdx = column("true_dx_m"), tdy = column("true_dy_m"), err = column("est_error_m"),
                    outside = column("true_outside_radius"), edyaw = column("est_dyaw_deg"),
                    tdyaw = column("true_dyaw_deg"), chi2 = column("prior_chi2"),
                    applied = column("prior_applied");
  // The motion prior: weighed once the prediction's error is measured (10 deviations), applied only
  // within its chi^2 gate.
  std::size_t weighed = 0;
  for (std::size_t i = 2; i < rows.size(); ++i) {
    const double c = std::stod(rows[i][chi2]);
    weighed += c >= 0;
    if (rows[i][applied] == "1") {
      EXPECT_LE(c, radarslam::RefineParams{}.motion_prior_chi2) << "row " << i;
    }
    if (c < 0) {
      EXPECT_EQ(rows[i][applied], "0") << "row " << i;
    }
  }
  EXPECT_GT(weighed, 20u);
  EXPECT_EQ(rows[1][status], "initialised");
  EXPECT_EQ(rows[1][tdx], "");  // no previous scan: no true motion
  const radarslam::Trajectory t = radarslam::readTumTrajectory(traj);
  ASSERT_EQ(t.size(), 40u);
  const auto reader = radarslam::openDataset(data);
  const std::set<std::string> statuses{"tracking", "lost", "recovered"};
  std::size_t outside_count = 0, compared = 0;
  // The heading summary's figures, from the rows: straight and turning tracked scans.
  std::size_t straight = 0, turning = 0;
  double straight_error = 0, turn_estimated = 0, turn_true = 0;
  bool borderline = false;  // a true turn within the CSV's rounding of a class bound
  for (std::size_t i = 2; i < rows.size(); ++i) {
    const auto& row = rows[i];
    ASSERT_EQ(row.size(), header.size()) << "row " << i;
    EXPECT_TRUE(statuses.count(row[status])) << row[status];
    auto num = [&row](std::size_t c) { return std::stod(row[c]); };
    // The estimated motion is the trajectory's step; the true one the ground truth's.
    const auto est = t[i - 1].pose - t[i - 2].pose;
    EXPECT_NEAR(num(edx), est.x, 2e-4);
    EXPECT_NEAR(num(edy), est.y, 2e-4);
    const auto g0 = reader->groundTruthAt(t[i - 2].stamp), g1 = reader->groundTruthAt(t[i - 1].stamp);
    if (!g0 || !g1) {  // the ground truth does not cover this step: no truth columns
      EXPECT_EQ(row[tdx], "");
      continue;
    }
    ++compared;
    const auto truth = *g1 - *g0;
    EXPECT_NEAR(num(tdx), truth.x, 2e-4);
    EXPECT_NEAR(num(tdy), truth.y, 2e-4);
    EXPECT_NEAR(num(err), std::hypot(est.x - truth.x, est.y - truth.y), 2e-3);
    const double pred_error = std::hypot(num(tdx) - num(pdx), num(tdy) - num(pdy));
    if (std::abs(pred_error - num(radius)) > 1e-3) {
      EXPECT_EQ(row[outside], pred_error > num(radius) ? "1" : "0");
    }
    outside_count += row[outside] == "1";
    if (row[status] != "lost") {
      const double turn = num(tdyaw), estimated = num(edyaw);
      borderline |= std::abs(std::abs(turn) - 0.05) < 2e-4 || std::abs(std::abs(turn) - 0.5) < 2e-4;
      if (std::abs(turn) < 0.05) {
        ++straight;
        straight_error += estimated - turn;
      } else if (std::abs(turn) >= 0.5) {
        ++turning;
        turn_true += std::abs(turn);
        turn_estimated += turn < 0 ? -estimated : estimated;
      }
    }
    if (i > 2) {
      EXPECT_GT(num(radius), 0.0);
    }
  }
  EXPECT_NE(r.out.find("true motion outside the search radius in " + std::to_string(outside_count) + " of " +
                       std::to_string(compared) + " scans"),
            std::string::npos)
      << r.out;
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(r.out, m,
                        std::regex("heading +straight scans \\(true turn < 0\\.05 deg\\): (mean error "
                                   "([-+0-9.]+) deg per scan over ([0-9]+) scans|none); turning scans "
                                   "\\(>= 0\\.5 deg\\): (([0-9.]+) % of the true turn estimated over "
                                   "([0-9]+) scans|none)\n")))
      << r.out;
  if (borderline) return;
  ASSERT_GT(straight, 0u);  // the drive starts on a straight road
  EXPECT_EQ(std::stoul(m[3].str()), straight);
  EXPECT_NEAR(std::stod(m[2].str()), straight_error / straight, 2e-4);
  if (turning == 0) {
    EXPECT_EQ(m[4].str(), "none");
  } else {
    EXPECT_EQ(std::stoul(m[6].str()), turning);
    EXPECT_NEAR(std::stod(m[5].str()), 100.0 * turn_estimated / turn_true, 0.1);
  }
}

TEST(CliOdometry, StepsFileIsValidatedBeforeTheRun) {
  namespace fs = std::filesystem;
  const fs::path data = radarslam::test::simulatedDataset("--scans 40");
  radarslam::test::TempDir tmp;
  const auto traj = tmp / "t.tum";
  Result r = runOdometry(
      "'" + data.string() + "' -o '" + traj.string() + "' --steps '" + traj.string() + "' -q", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--steps"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(traj));
  fs::create_symlink("t.tum", tmp / "alias.csv");  // the trajectory file under another name
  r = runOdometry(
      "'" + data.string() + "' -o '" + traj.string() + "' --steps '" + (tmp / "alias.csv").string() + "' -q",
      tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("same file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(traj));
  r = runOdometry(
      "'" + data.string() + "' -o '" + traj.string() + "' --steps '" + tmp.path().string() + "' -q", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(traj));
}

}  // namespace
