// The simulator's output is a valid Oxford Radar RobotCar sequence, and reads back through io.
#include <gtest/gtest.h>

#include <mrpt/poses/CPose2D.h>

#include <opencv2/imgcodecs.hpp>

#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "radarslam/io/dataset.h"
#include "radarslam/sim/simulator.h"
#include "sim_test_util.h"
#include "temp_dir.h"

using namespace radarslam;
using namespace radarslam::sim;
namespace fs = std::filesystem;

namespace {
std::vector<std::string> lines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}
std::vector<std::string> fields(const std::string& l) {
  std::vector<std::string> f;
  std::stringstream ss(l);
  for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
  return f;
}
}  // namespace

class SimOxfordFormat : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    auto c = simtest::smallConfig(5, kScans);
    sim_ = new Simulation(c);
    simulateToDirectory(c, dir_->path());
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete dir_;
  }
  static constexpr int kScans = 6;
  static test::TempDir* dir_;
  static Simulation* sim_;
};
test::TempDir* SimOxfordFormat::dir_ = nullptr;
Simulation* SimOxfordFormat::sim_ = nullptr;

TEST_F(SimOxfordFormat, PngsHaveOxfordLayoutAndFileNameIsFirstAzimuthStamp) {
  const fs::path root = dir_->path();
  const auto stamps = lines(root / "radar.timestamps");
  ASSERT_EQ(stamps.size(), static_cast<std::size_t>(kScans));
  for (int i = 0; i < kScans; ++i) {
    const std::int64_t name = sim_->scanStart(static_cast<std::size_t>(i)) / kNsPerUs;
    EXPECT_EQ(stamps[static_cast<std::size_t>(i)], std::to_string(name) + " 1");
    const cv::Mat img =
        cv::imread((root / "radar" / (std::to_string(name) + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(img.empty()) << name;
    EXPECT_EQ(img.type(), CV_8UC1);
    EXPECT_EQ(img.rows, 100);
    EXPECT_EQ(img.cols, 11 + 600);
    for (int a = 0; a < img.rows; ++a) {
      std::int64_t t = 0;
      std::memcpy(&t, img.ptr<std::uint8_t>(a), 8);  // little-endian host
      std::uint16_t enc = 0;
      std::memcpy(&enc, img.ptr<std::uint8_t>(a) + 8, 2);
      if (a == 0) {
        EXPECT_EQ(t, name);
      }
      EXPECT_EQ(t, name + a * 2500);
      EXPECT_EQ(enc, (a + 1) * 56 - 1);
      EXPECT_EQ(img.at<std::uint8_t>(a, 10), 255);
    }
  }
}

TEST_F(SimOxfordFormat, GroundTruthHasOxfordSemanticsAndChainsToTheTruth) {
  const fs::path root = dir_->path();
  const auto csv = lines(root / "gt" / "radar_odometry.csv");
  ASSERT_EQ(csv.size(), static_cast<std::size_t>(kScans));  // header + one row per pair
  EXPECT_EQ(csv[0],
            "source_timestamp,destination_timestamp,x,y,z,roll,pitch,yaw,source_radar_timestamp,"
            "destination_radar_timestamp");
  const Trajectory truth = sim_->scanTruth();
  ASSERT_EQ(truth.size(), static_cast<std::size_t>(kScans));
  mrpt::poses::CPose2D chained(truth[0].pose);
  for (int k = 1; k < kScans; ++k) {
    const auto f = fields(csv[static_cast<std::size_t>(k)]);
    ASSERT_EQ(f.size(), 10u);
    EXPECT_EQ(std::stoll(f[0]), truth[static_cast<std::size_t>(k)].stamp / kNsPerUs);      // mid-sweep, later
    EXPECT_EQ(std::stoll(f[1]), truth[static_cast<std::size_t>(k - 1)].stamp / kNsPerUs);  // earlier
    EXPECT_EQ(std::stoll(f[8]), sim_->scanStart(static_cast<std::size_t>(k)) / kNsPerUs);  // file names
    EXPECT_EQ(std::stoll(f[9]), sim_->scanStart(static_cast<std::size_t>(k - 1)) / kNsPerUs);
    EXPECT_EQ(std::stoll(f[0]) - std::stoll(f[8]), 99 * 2500 / 2);  // mid-sweep, as Oxford
    for (int z : {4, 5, 6}) EXPECT_EQ(std::stod(f[static_cast<std::size_t>(z)]), 0.0);
    chained = chained + mrpt::poses::CPose2D(std::stod(f[2]), std::stod(f[3]), std::stod(f[7]));
    const auto& t = truth[static_cast<std::size_t>(k)].pose;
    EXPECT_NEAR(chained.x(), t.x, 1e-6);
    EXPECT_NEAR(chained.y(), t.y, 1e-6);
    EXPECT_NEAR(std::remainder(chained.phi() - t.phi, 2 * M_PI), 0.0, 1e-8);
  }
  const auto tum = lines(root / "gt" / "poses.tum");
  ASSERT_EQ(tum.size(), static_cast<std::size_t>(kScans) + 1);  // comment + poses
  std::istringstream first(tum[1]);
  double t, x, y, z, qx, qy, qz, qw;
  first >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
  EXPECT_NEAR(t, toSeconds(truth[0].stamp), 1e-6);
  EXPECT_NEAR(x, truth[0].pose.x, 1e-5);
  EXPECT_NEAR(2 * std::atan2(qz, qw), truth[0].pose.phi, 1e-8);
}

TEST_F(SimOxfordFormat, ReadsBackThroughTheDatasetReader) {
  const auto reader = openDataset(dir_->path());
  EXPECT_EQ(reader->kind(), DatasetKind::Oxford);
  ASSERT_EQ(reader->size(), static_cast<std::size_t>(kScans));
  const Trajectory truth = sim_->scanTruth();
  const mrpt::poses::CPose2D origin(truth[0].pose);
  CObservationRadarScan expected;
  for (std::size_t i = 0; i < reader->size(); ++i) {
    const auto scan = reader->readScan(i);
    sim_->render(i, expected);
    EXPECT_EQ(scan->num_azimuths, 100u);
    EXPECT_EQ(scan->num_bins, 600u);
    EXPECT_EQ(scan->power, expected.power);
    EXPECT_EQ(scan->azimuth_stamps_ns, expected.azimuth_stamps_ns);
    for (std::size_t a = 0; a < scan->num_azimuths; ++a)
      EXPECT_NEAR(scan->azimuth_angles_rad[a], expected.azimuth_angles_rad[a], 1e-9);
    EXPECT_EQ(scan->refStampNs(), truth[i].stamp);
    // The reader chains the relative GT from the first scan: compare relative to it.
    const auto gt = reader->groundTruthAt(scan->refStampNs());
    ASSERT_TRUE(gt.has_value()) << i;
    const mrpt::poses::CPose2D rel = mrpt::poses::CPose2D(truth[i].pose) - origin;
    EXPECT_NEAR(gt->x, rel.x(), 1e-3);
    EXPECT_NEAR(gt->y, rel.y(), 1e-3);
    EXPECT_NEAR(std::remainder(gt->phi - rel.phi(), 2 * M_PI), 0.0, 1e-5);
  }
}

TEST_F(SimOxfordFormat, LeavesNoTemporaryFiles) {
  // No temporary files are left behind by the atomic writes.
  for (const auto& e : fs::recursive_directory_iterator(dir_->path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}
