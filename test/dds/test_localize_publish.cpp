// `radarslam localize` on DDS, real processes on loopback (docs/dds.md): --publish sends one
// PoseWithCovarianceStamped per localised scan, identical to the TUM/CSV outputs, and one
// LocalizationStatus per scan (lost ones too) agreeing with the CSV; DIR = dds: takes the scans
// from radarslam-scan-publisher.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <radarslam/dds/domain.h>
#include <radarslam/dds/pose_publisher.h>
#include <radarslam/io/trajectory_files.h>
#include <radarslam/map/map_io.h>

#include "dds_test_util.h"
#include "simulated_dataset.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

/// Data rows (not starting with '#') of a whitespace-separated file.
std::vector<std::vector<std::string>> rows(const fs::path& p) {
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

/// Runs `radarslam ARGS` to completion; returns the exit code (stderr in `log`.err).
int runCli(const std::vector<std::string>& args, const fs::path& log, double timeout_s = 60) {
  std::vector<std::string> all{RADARSLAM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  test::Child c(all, log);
  return c.wait(timeout_s);
}

/// A 40-scan simulated drive (test/support/simulated_dataset.h: simulated once for all tests, read
/// only) and a map-synth map of it (ground-truth keyframes).
struct SmallWorld {
  test::TempDir tmp;
  fs::path data = test::simulatedDataset("--scans 40"), map = tmp.path() / "map";
  SmallWorld() {
    EXPECT_EQ(runCli({"map-synth", data.string(), "-o", map.string()}, tmp.path() / "synth"), 0)
        << test::readText(tmp.path() / "synth.err");
  }
};

TEST(LocalizePublish, PublishedPosesEqualTheWrittenPoses) {
  SmallWorld w;
  ASSERT_FALSE(HasFailure());
  const unsigned dom_id = test::testDomainId(10);
  dds::Domain dom(dom_id);
  dds::Subscription<dds::PoseWithCovarianceStampedMsg> sub(dom, dds::kPoseTopic, dds::TopicQos::stream(200));
  dds::Subscription<dds::LocalizationStatusMsg> status_sub(dom, dds::kLocalizationStatusTopic,
                                                           dds::TopicQos::stream(200));
  const fs::path out = w.tmp.path() / "out.tum";
  test::Child loc(
      {RADARSLAM_CLI, "localize", w.map.string(), w.data.string(), "-o", out.string(), "--publish",
       "--domain", std::to_string(dom_id), "--wait-subscribers", "1", "--dds-timeout", "10", "-q"},
      w.tmp.path() / "loc");
  std::vector<dds::PoseWithCovarianceStampedMsg> got;
  std::vector<dds::LocalizationStatusMsg> statuses;
  const auto deadline = std::chrono::steady_clock::now() + 60s * test::timeScale();
  for (bool exited = false;;) {
    bool any = false;
    while (auto st = status_sub.take(0ms)) statuses.push_back(*st), any = true;
    if (auto m = sub.take(200ms)) {
      got.push_back(*m);
    } else if (any) {
      continue;
    } else if (exited || std::chrono::steady_clock::now() > deadline) {
      break;
    } else {
      exited = !loc.running();  // one more empty take after the exit
    }
  }
  ASSERT_EQ(loc.wait(10), 0) << loc.err();
  EXPECT_NE(loc.out().find("published"), std::string::npos) << loc.out();

  const auto tum = rows(out);
  const auto all_rows = rows(out.string() + ".csv");
  // One status per scan, in order, agreeing with the CSV; pose_published exactly for localised scans.
  ASSERT_EQ(statuses.size(), all_rows.size()) << loc.err();
  std::size_t with_pose = 0;
  for (std::size_t i = 0; i < statuses.size(); ++i) {
    const auto& st = statuses[i];
    const auto& r = all_rows[i];
    EXPECT_EQ(formatStampSeconds(dds::fromTimeMsg(st.header.stamp)), r[0]) << i;
    EXPECT_EQ(st.status, r[2]) << i;
    EXPECT_EQ(st.pose_published, r[3] == "1") << i;
    EXPECT_EQ(st.level, r[2] == "lost" ? 2 : r[2] == "degraded" ? 1 : 0) << i;
    if (st.pose_published) {
      ++with_pose;
      EXPECT_GE(st.keyframe, 0) << i;
      EXPECT_NEAR(st.sigma_yaw_rad, std::sqrt(std::stod(r[12])), 1e-4 * std::sqrt(std::stod(r[12]))) << i;
      EXPECT_GE(st.sigma_xy_m * st.sigma_xy_m * (1 + 1e-4), std::max(std::stod(r[7]), std::stod(r[10]))) << i;
    } else {
      EXPECT_EQ(st.keyframe, -1) << i;
      EXPECT_EQ(st.sigma_xy_m, 0.0) << i;
    }
  }
  EXPECT_GE(statuses.back().global_fixes, 1u);
  std::vector<std::vector<std::string>> side;
  for (const auto& r : all_rows)
    if (r[3] == "1") side.push_back(r);
  EXPECT_EQ(with_pose, side.size());
  ASSERT_GE(tum.size(), 30u) << loc.out();  // the localiser itself works on this world
  ASSERT_EQ(side.size(), tum.size());
  ASSERT_EQ(got.size(), tum.size()) << loc.err();
  for (std::size_t i = 0; i < got.size(); ++i) {
    const auto& m = got[i];
    const auto& t = tum[i];
    EXPECT_EQ(m.header.frame_id, "map");
    // Stamps: the file has 9 decimals of seconds (exact ns).
    EXPECT_EQ(formatStampSeconds(dds::fromTimeMsg(m.header.stamp)), t[0]) << i;
    EXPECT_NEAR(m.pose.x, std::stod(t[1]), 1e-6) << i;
    EXPECT_NEAR(m.pose.y, std::stod(t[2]), 1e-6) << i;
    EXPECT_NEAR(m.pose.qz, std::stod(t[6]), 1e-6) << i;
    EXPECT_NEAR(m.pose.qw, std::stod(t[7]), 1e-6) << i;
    EXPECT_NEAR(dds::poseFromMessage(m).phi, std::stod(side[i][6]), 1e-6) << i;
    // Covariance: (x, y, phi) at the (x, y, rot z) entries of the 6x6 ROS layout; CSV has 6 digits.
    const double cxx = std::stod(side[i][7]), cxy = std::stod(side[i][8]), cxp = std::stod(side[i][9]);
    const double cyy = std::stod(side[i][10]), cyp = std::stod(side[i][11]), cpp = std::stod(side[i][12]);
    auto near = [](double a, double b) { return std::abs(a - b) <= 1e-5 * std::abs(b) + 1e-15; };
    EXPECT_TRUE(near(m.covariance[0], cxx)) << i << " " << m.covariance[0] << " vs " << cxx;
    EXPECT_TRUE(near(m.covariance[1], cxy)) << i;
    EXPECT_TRUE(near(m.covariance[6], cxy)) << i;
    EXPECT_TRUE(near(m.covariance[5], cxp)) << i;
    EXPECT_TRUE(near(m.covariance[30], cxp)) << i;
    EXPECT_TRUE(near(m.covariance[7], cyy)) << i;
    EXPECT_TRUE(near(m.covariance[11], cyp)) << i;
    EXPECT_TRUE(near(m.covariance[35], cpp)) << i;
    EXPECT_GT(m.covariance[0], 0) << i;
  }
}

TEST(LocalizePublish, LocalisesScansFromTheScanPublisher) {
  SmallWorld w;
  ASSERT_FALSE(HasFailure());
  const unsigned dom_id = test::testDomainId(11);
  const fs::path out = w.tmp.path() / "out.tum";
  test::Child loc({RADARSLAM_CLI, "localize", w.map.string(), "dds:", "-o", out.string(), "--domain",
                   std::to_string(dom_id), "--dds-timeout", "3", "--sensor", "oxford", "--scan-queue", "64"},
                  w.tmp.path() / "loc");
  // Paced by the scan stamps (4 Hz); --scan-queue 64 keeps every scan even when the (loaded)
  // machine localises slower than 4 Hz.
  test::Child pub({RADARSLAM_SCAN_PUBLISHER, w.data.string(), "--domain", std::to_string(dom_id), "--rate",
                   "1", "--wait-subscribers", "1", "--wait-timeout", "20"},
                  w.tmp.path() / "pub");
  ASSERT_EQ(pub.wait(40), 0) << pub.err();
  ASSERT_EQ(loc.wait(60), 0) << loc.err();
  const auto side = rows(out.string() + ".csv");
  std::size_t localised = 0;
  for (const auto& r : side) localised += r[3] == "1";
  EXPECT_EQ(side.size(), 40u) << loc.out();         // every published scan was processed
  EXPECT_GE(localised * 10, 40u * 9) << loc.out();  // >= 90 % of the 40 scans localised
  EXPECT_EQ(rows(out).size(), localised);
  EXPECT_NE(loc.err().find("DDS scans"), std::string::npos) << loc.err();
  EXPECT_NE(loc.err().find("localize: 40 DDS scans,"), std::string::npos) << loc.err();  // progress
  EXPECT_EQ(loc.err().find("ETA"), std::string::npos) << loc.err();                      // no ETA
}

TEST(LocalizePublish, NoScanWithinTheTimeoutIsAOneLineError) {
  test::TempDir tmp;
  saveMap(test::syntheticMap(3, 200, 30.0, 1), tmp.path() / "map");
  const int rc =
      runCli({"localize", (tmp.path() / "map").string(), "dds:", "-o", (tmp.path() / "o.tum").string(),
              "--domain", std::to_string(test::testDomainId(12)), "--dds-timeout", "0.5", "-q"},
             tmp.path() / "loc");
  EXPECT_EQ(rc, 1);
  const std::string e = test::readText(tmp.path() / "loc.err");
  EXPECT_NE(e.find("no scan received"), std::string::npos) << e;
}

}  // namespace
}  // namespace radarslam
