// Boreas: synthetic scans in all three geometries, and the two real radar_poses.csv files.
#include <gtest/gtest.h>

#include <mrpt/math/wrap2pi.h>

#include <cmath>
#include <numbers>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/ground_truth.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;

namespace {
struct Geometry {
  const char* name;
  std::int64_t t0_us;  // first azimuth of the first scan
  int bins;
  double expected_resolution;
  const char* expected_sensor;
};

// Two scans in the Boreas layout: us stamps, file name = middle azimuth (row M/2 - 1).
void writeBoreasSequence(const std::filesystem::path& root, const Geometry& g, int azimuths,
                         bool with_applanix = true) {
  for (int s = 0; s < 2; ++s) {
    const auto sweep = test::makeSweep(azimuths, g.t0_us + s * 250'000, 625, 7);
    test::writeOxfordStylePng(root / "radar" / (std::to_string(sweep.stamps[azimuths / 2 - 1]) + ".png"),
                              sweep.stamps, sweep.encoders, sweep.valid, g.bins);
  }
  if (with_applanix) std::filesystem::create_directories(root / "applanix");
}
}  // namespace

class BoreasGeometry : public ::testing::TestWithParam<Geometry> {};

TEST_P(BoreasGeometry, SyntheticScansDecodeWithTheRightGeometry) {
  const Geometry g = GetParam();
  test::TempDir tmp;
  constexpr int kAz = 20;
  writeBoreasSequence(tmp.path(), g, kAz);
  const auto reader = openDataset(tmp.path());
  EXPECT_EQ(reader->kind(), DatasetKind::Boreas);
  EXPECT_EQ(reader->sensorName(), g.expected_sensor);
  ASSERT_EQ(reader->size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    const auto scan = reader->readScan(s);
    EXPECT_EQ(scan->checkConsistency(), "");
    EXPECT_EQ(scan->num_bins, static_cast<std::uint32_t>(g.bins));
    EXPECT_EQ(scan->num_azimuths, static_cast<std::uint32_t>(kAz));
    EXPECT_DOUBLE_EQ(scan->range_resolution_m, g.expected_resolution);
    EXPECT_DOUBLE_EQ(scan->range_offset_m, -0.31);
    EXPECT_EQ(reader->indexStamp(s), scan->azimuth_stamps_ns[kAz / 2 - 1]);  // middle azimuth
    EXPECT_EQ(scan->azimuth_stamps_ns[0], (g.t0_us + static_cast<std::int64_t>(s) * 250'000) * 1000);
    // Column 10 alternates 0/255 in the synthetic data: Boreas ignores it, all azimuths valid.
    EXPECT_EQ(std::count(scan->azimuth_valid.begin(), scan->azimuth_valid.end(), 1), kAz);
    // RAS6: column 10 is the chirp flag (255 up, 0 down); the CIR204-H has a single chirp.
    const bool ras6 = g.bins == 6848;
    EXPECT_EQ(scan->hasChirpDirections(), ras6);
    for (int r = 0; r < kAz; ++r)
      EXPECT_EQ(scan->chirp(static_cast<std::size_t>(r)), ras6 ? (r % 2 ? 1 : -1) : 0) << "azimuth " << r;
    EXPECT_EQ(scan->row(3)[g.bins - 1], test::syntheticPower(3, g.bins - 1));
  }
  // Ground truth: one absolute pose per scan stamp (us), z-down radar (roll pi) heading north-east
  // (pyboreas heading = angle of the sensor x from east, counter-clockwise).
  std::string csv =
      "GPSTime,easting,northing,altitude,vel_east,vel_north,vel_up,roll,pitch,heading,angvel_z,angvel_y,"
      "angvel_x\n";
  for (std::size_t s = 0; s < 2; ++s)
    csv += std::to_string(reader->indexStamp(s) / 1000) + "," + std::to_string(623000.0 + 2.0 * s) + "," +
           std::to_string(4848000.0 + 2.0 * s) + ",150,0,0,0,3.14159265358979,0,0.785398163397448,0,0,0\n";
  test::writeText(tmp / "applanix" / "radar_poses.csv", csv);
  const auto with_gt = openDataset(tmp.path());
  ASSERT_TRUE(with_gt->hasGroundTruth());
  ASSERT_EQ(with_gt->groundTruth().size(), 2u);
  EXPECT_EQ(with_gt->groundTruth()[1].stamp, reader->indexStamp(1));
  const auto p0 = with_gt->groundTruth()[0].pose, p1 = with_gt->groundTruth()[1].pose;
  // Moving along the heading: the displacement direction equals the SE(2) yaw.
  EXPECT_NEAR(std::atan2(p1.y - p0.y, p1.x - p0.x), p1.phi, 1e-6);
  // A resolution given in the options wins.
  ReaderOptions o;
  o.range_resolution_m = 0.05;
  o.range_offset_m = 0.0;
  const auto scan = openDataset(tmp.path(), o)->readScan(0);
  EXPECT_DOUBLE_EQ(scan->range_resolution_m, 0.05);
  EXPECT_DOUBLE_EQ(scan->range_offset_m, 0.0);
}

// Downloaded radar-only (no applanix/, no calib/): recognised from the scans themselves.
TEST_P(BoreasGeometry, RadarOnlyFolderIsRecognisedFromTheScans) {
  const Geometry g = GetParam();
  test::TempDir tmp;
  writeBoreasSequence(tmp.path(), g, 20, /*with_applanix=*/false);
  const auto reader = openDataset(tmp.path());
  EXPECT_EQ(reader->kind(), DatasetKind::Boreas);
  EXPECT_EQ(reader->sensorName(), g.expected_sensor);
  EXPECT_FALSE(reader->hasGroundTruth());
  ASSERT_EQ(reader->size(), 2u);
  EXPECT_EQ(reader->readScan(1)->num_bins, static_cast<std::uint32_t>(g.bins));
  EXPECT_DOUBLE_EQ(reader->readScan(1)->range_resolution_m, g.expected_resolution);
}

INSTANTIATE_TEST_SUITE_P(
    AllThree, BoreasGeometry,
    ::testing::Values(Geometry{"CIR204_before_upgrade", 1628184886551599LL, 3360, 0.0596, "Navtech CIR204-H"},
                      Geometry{"CIR204_after_upgrade", 1632182400LL * 1'000'000 + 3600'000'000LL, 3360,
                               0.04381, "Navtech CIR204-H"},
                      Geometry{"RAS6", 1733248400LL * 1'000'000, 6848, 0.04381, "Navtech RAS6"}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

// A RAS6 scan whose flag column never changes has no alternating chirp: directions stay unknown.
TEST(BoreasChirp, ConstantFlagColumnIsNotAnAlternatingChirp) {
  for (const std::uint8_t flag : {std::uint8_t{0}, std::uint8_t{255}}) {
    test::TempDir tmp;
    auto sweep = test::makeSweep(20, 1733248400LL * 1'000'000, 625, 7);
    std::fill(sweep.valid.begin(), sweep.valid.end(), flag);
    test::writeOxfordStylePng(tmp / "radar" / (std::to_string(sweep.stamps[9]) + ".png"), sweep.stamps,
                              sweep.encoders, sweep.valid, 6848);
    const auto scan = openDataset(tmp.path())->readScan(0);
    EXPECT_FALSE(scan->hasChirpDirections()) << "flag " << int{flag};
    EXPECT_EQ(scan->checkConsistency(), "");
  }
}

// radar/ alone whose scans are not of a Boreas geometry is not guessed to be Boreas.
TEST(BoreasDetection, RadarFolderOfOtherScansIsStillAnError) {
  test::TempDir tmp;
  const auto sweep = test::makeSweep(20, 1628184886551599LL, 625, 7);
  test::writeOxfordStylePng(tmp / "radar" / (std::to_string(sweep.stamps[9]) + ".png"), sweep.stamps,
                            sweep.encoders, sweep.valid, 3768);  // Oxford width, but no radar.timestamps
  test::expectInputError([&] { openDataset(tmp.path()); }, "radar.timestamps", "missing radar.timestamps");
}

namespace {
void checkBoreasGroundTruth(const std::filesystem::path& csv, std::size_t expected_rows,
                            StampNs day_start_s) {
  const auto gt = readBoreasGroundTruth(csv);
  ASSERT_EQ(gt.size(), expected_rows);
  EXPECT_FALSE(firstNonIncreasingStamp(gt).has_value());
  // Whatever the file's unit (ns or us), stamps come out as ns on the recording day, ~4 Hz.
  EXPECT_GE(gt.front().stamp, day_start_s * kNsPerSec);
  EXPECT_LT(gt.front().stamp, (day_start_s + 86400) * kNsPerSec);
  const double minutes = toSeconds(gt.back().stamp - gt.front().stamp) / 60.0;
  EXPECT_GT(minutes, 15.0);
  EXPECT_LT(minutes, 21.0);
  EXPECT_NEAR(pathLength(gt) / 1000.0, 7.9, 0.3);
  // Convention check: the radar's x axis points forward, so when driving the direction of motion
  // in the SE(2) world matches the SE(2) yaw. A sign error in the projection (no flip for the
  // z-down radar) would make it the mirror image -> large errors whenever the heading != 0/180.
  std::size_t moving = 0, aligned = 0;
  for (std::size_t i = 1; i < gt.size(); ++i) {
    const double dx = gt[i].pose.x - gt[i - 1].pose.x, dy = gt[i].pose.y - gt[i - 1].pose.y;
    if (std::hypot(dx, dy) < 1.0) continue;
    ++moving;
    if (std::abs(mrpt::math::wrapToPi(std::atan2(dy, dx) - gt[i].pose.phi)) < 0.1) ++aligned;
  }
  EXPECT_GT(moving, 2000u);
  EXPECT_GT(static_cast<double>(aligned) / static_cast<double>(moving), 0.95);
}
}  // namespace

TEST(BoreasGroundTruth, NanosecondFile) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "boreas_gt_only/boreas-2021-08-05-13-34");
  checkBoreasGroundTruth(dir / "applanix" / "radar_poses.csv", 4477, 1628121600);
}

TEST(BoreasGroundTruth, MicrosecondFile) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "boreas_gt_only/boreas-2021-09-02-11-42");
  checkBoreasGroundTruth(dir / "applanix" / "radar_poses.csv", 4134, 1630540800);
}

TEST(BoreasGroundTruth, ProjectionFlipsAZDownSensor) {
  // A z-down sensor (roll = pi) whose x axis points along world +y (north): in the flipped world
  // (x, -y) its x axis points along -y, yaw -pi/2; its own y axis (azimuth 90 deg) points along
  // world +x, which in the flipped frame is reached by turning +90 deg from the sensor x.
  const mrpt::poses::CPose3D sensor(10, 20, 0, std::numbers::pi / 2, 0, std::numbers::pi);
  const auto p = projectSensorPoseToSE2(sensor);
  EXPECT_NEAR(p.x, 10, 1e-12);
  EXPECT_NEAR(p.y, -20, 1e-12);
  EXPECT_NEAR(p.phi, -std::numbers::pi / 2, 1e-12);
  // z-up sensors are projected as they are.
  const auto q = projectSensorPoseToSE2(mrpt::poses::CPose3D(1, 2, 3, 0.3, 0.01, 0.02));
  EXPECT_NEAR(q.y, 2, 1e-12);
  EXPECT_NEAR(q.phi, 0.3, 1e-3);
}

TEST(BoreasGroundTruth, MalformedRowsAreErrors) {
  test::TempDir tmp;
  const std::string header =
      "GPSTime,easting,northing,altitude,vel_east,vel_north,vel_up,roll,pitch,heading,angvel_z,angvel_y,"
      "angvel_x\n";
  test::writeText(tmp / "p.csv", header + "1630597331060160,1,2,3,0,0,0,3.1,0,0.2,0,0\n");
  test::expectInputError([&] { readBoreasGroundTruth(tmp / "p.csv"); }, "p.csv:2", "expected 13");
  test::writeText(tmp / "p.csv", header + "16305973310x0160,1,2,3,0,0,0,3.1,0,0.2,0,0,0\n");
  test::expectInputError([&] { readBoreasGroundTruth(tmp / "p.csv"); }, "p.csv:2", "not a UNIX timestamp");
}
