// Fault injection for the pipeline (issue #8 d): a simulated Oxford-format drive is damaged on
// disk the way real logs are - dropped scans, duplicated index lines, a burst of blank scans (the
// radar covered by snow), a timestamp jump - and `radarslam odometry` must still finish, report
// what it skipped or flagged, and give a continuous trajectory that ends near the ground truth.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "cli_run.h"
#include "radarslam/core/time.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/oxford_writer.h"
#include "radarslam/io/trajectory_files.h"
#include "temp_dir.h"

namespace {

using radarslam::test::runCli;
using Result = radarslam::test::CliResult;

namespace fs = std::filesystem;
using radarslam::StampNs;

std::size_t lineCount(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

// The faults, as indices of the 80 simulated scans.
constexpr int kScans = 80;
const std::set<int> kDropped = {12, 27, 40, 45, 70};  // index line and PNG removed
const std::set<int> kDuplicated = {20, 35, 60};       // index line written twice
constexpr int kFirstBlank = 48, kBlankCount = 8;      // power all zero (snow on the radome)
constexpr int kJumpFrom = 63;                         // this scan and all later ones: stamps + 10 s
constexpr StampNs kJumpNs = 10 * radarslam::kNsPerSec;

void writePng(const fs::path& file, const radarslam::CObservationRadarScan& scan) {
  const auto bytes = radarslam::encodeOxfordPng(scan);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << file;
}

/// Copies the Oxford-format dataset `src` to `dst` with the faults above (no ground truth).
void makeFaultyCopy(const fs::path& src, const fs::path& dst) {
  fs::create_directories(dst);
  fs::copy(src / "radar", dst / "radar", fs::copy_options::recursive);
  const auto reader = radarslam::openDataset(src);
  ASSERT_EQ(reader->size(), static_cast<std::size_t>(kScans));
  std::string index;
  for (int i = 0; i < kScans; ++i) {
    const StampNs us = reader->indexStamp(i) / radarslam::kNsPerUs;
    const fs::path png = dst / "radar" / (std::to_string(us) + ".png");
    if (kDropped.count(i)) {
      fs::remove(png);
      continue;
    }
    const bool blank = i >= kFirstBlank && i < kFirstBlank + kBlankCount;
    StampNs new_us = us;
    if (blank || i >= kJumpFrom) {
      auto scan = reader->readScan(i);
      if (blank) std::fill(scan->power.begin(), scan->power.end(), 0);
      if (i >= kJumpFrom) {
        for (auto& t : scan->azimuth_stamps_ns) t += kJumpNs;
        new_us += kJumpNs / radarslam::kNsPerUs;
        fs::remove(png);
      }
      writePng(dst / "radar" / (std::to_string(new_us) + ".png"), *scan);
    }
    const std::string line = std::to_string(new_us) + " 1\n";
    index += line;
    if (kDuplicated.count(i)) index += line;
  }
  std::ofstream(dst / "radar.timestamps") << index;
}

class CliFaultInjection : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new radarslam::test::TempDir;
    ASSERT_EQ(runCli("simulate '" + (*tmp_ / "sim").string() + "' --scans 80 --seed 5", *tmp_).code, 0);
    makeFaultyCopy(*tmp_ / "sim", *tmp_ / "faulty");
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  static radarslam::test::TempDir* tmp_;
};
radarslam::test::TempDir* CliFaultInjection::tmp_ = nullptr;

TEST_F(CliFaultInjection, OdometryFinishesReportsFaultsAndStaysContinuous) {
  radarslam::test::TempDir tmp;
  const auto traj_file = tmp / "faulty.tum";
  const Result r =
      runCli("odometry '" + (*tmp_ / "faulty").string() + "' -o '" + traj_file.string() + "' -q", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  // The summary names every fault: 3 duplicates skipped, 8 blank scans, 5 gaps from the dropped
  // scans (0.5 s > 1.5 x 0.25 s) plus the 10 s jump.
  EXPECT_NE(r.out.find("3 duplicate scans skipped"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("8 blank scans"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("6 time gaps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("largest 10.250 s"), std::string::npos) << r.out;

  const radarslam::Trajectory out = radarslam::readTumTrajectory(traj_file);
  ASSERT_EQ(out.size(), static_cast<std::size_t>(kScans) - kDropped.size());  // duplicates skipped once

  // Ground truth of the undamaged drive, at each output pose's original time (jump undone).
  const auto original = radarslam::openDataset(*tmp_ / "sim");
  const radarslam::Trajectory& gt = original->groundTruth();
  const StampNs jump_threshold = original->indexStamp(kJumpFrom) + kJumpNs / 2;
  auto originalTime = [&](StampNs t) { return t >= jump_threshold ? t - kJumpNs : t; };
  double vmax = 0;
  for (std::size_t i = 1; i < gt.size(); ++i)
    vmax = std::max(vmax, std::hypot(gt[i].pose.x - gt[i - 1].pose.x, gt[i].pose.y - gt[i - 1].pose.y) /
                              radarslam::toSeconds(gt[i].stamp - gt[i - 1].stamp));
  ASSERT_GT(vmax, 1.0);

  // Continuous: no step longer than the fastest ground-truth motion over the real elapsed time
  // (across the jump that is one scan period, not 10 s) plus 2 m.
  double gt_length = 0;
  std::size_t last_with_gt = 0;
  for (std::size_t i = 1; i < out.size(); ++i) {
    const double dt = radarslam::toSeconds(originalTime(out[i].stamp) - originalTime(out[i - 1].stamp));
    ASSERT_GT(dt, 0.0) << "pose " << i;
    const double step = std::hypot(out[i].pose.x - out[i - 1].pose.x, out[i].pose.y - out[i - 1].pose.y);
    EXPECT_LE(step, vmax * dt + 2.0) << "pose " << i << " (dt " << dt << " s)";
    const auto g0 = radarslam::interpolatePose(gt, originalTime(out[i - 1].stamp));
    const auto g1 = radarslam::interpolatePose(gt, originalTime(out[i].stamp));
    if (!g0 || !g1) continue;  // the ground truth ends at the last pair's mid-sweep times
    gt_length += std::hypot(g1->x - g0->x, g1->y - g0->y);
    last_with_gt = i;
  }
  ASSERT_GE(last_with_gt, out.size() - 2) << "the ground truth should cover all but the last scan";

  // Final position relative to the start, against the ground truth's: within 10 % of the path.
  const auto gt_first = radarslam::interpolatePose(gt, originalTime(out.front().stamp));
  const auto gt_last = radarslam::interpolatePose(gt, originalTime(out[last_with_gt].stamp));
  ASSERT_TRUE(gt_first && gt_last);
  const mrpt::math::TPose2D gt_rel = *gt_last - *gt_first;
  const mrpt::math::TPose2D est_rel = out[last_with_gt].pose - out.front().pose;
  const double error = std::hypot(est_rel.x - gt_rel.x, est_rel.y - gt_rel.y);
  std::printf("faulty drive: %.1f m, final position error %.2f m (%.1f %%), vmax %.1f m/s\n", gt_length,
              error, 100 * error / gt_length, vmax);
  EXPECT_GT(gt_length, 20.0);
  EXPECT_LT(error, 0.10 * gt_length);
}

TEST_F(CliFaultInjection, TimestampsGoingBackwardsAreAOneLineError) {
  radarslam::test::TempDir tmp;
  const fs::path bad = tmp / "backwards";
  fs::copy(*tmp_ / "faulty", bad, fs::copy_options::recursive);
  std::ifstream in(bad / "radar.timestamps");
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::swap(lines[5], lines[6]);  // line 7 is earlier than line 6
  std::ofstream o(bad / "radar.timestamps");
  for (const auto& l : lines) o << l << "\n";
  o.close();
  for (const char* skip : {"", " --skip-bad-scans"}) {
    const Result r =
        runCli("odometry '" + bad.string() + "' -o '" + (tmp / "x.tum").string() + "' -q" + skip, tmp);
    EXPECT_EQ(r.code, 1) << skip;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("radar.timestamps:7"), std::string::npos) << r.err;
  }
}

}  // namespace
