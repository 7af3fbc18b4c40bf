// The simulator renders other Navtech geometries (config/sim_mulran.yaml, config/sim_boreas.yaml)
// and the sequence it writes reads back with that geometry, not Oxford's.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include "radarslam/io/dataset.h"
#include "radarslam/radar/cartesian.h"
#include "radarslam/sim/simulator.h"
#include "temp_dir.h"

using namespace radarslam;
using namespace radarslam::sim;

namespace {
struct Variant {
  const char* config;
  int bins;
  double resolution_m;
};

class SensorVariant : public ::testing::TestWithParam<Variant> {};
}  // namespace

TEST_P(SensorVariant, RendersAndReadsBackItsOwnGeometry) {
  const Variant v = GetParam();
  SimulationConfig c;
  loadSimulationConfig(std::string(RADARSLAM_SOURCE_DIR) + "/config/" + v.config, c);
  EXPECT_EQ(c.geometry.bins, v.bins);
  EXPECT_DOUBLE_EQ(c.geometry.range_resolution_m, v.resolution_m);
  c.scans = 2;
  const test::TempDir dir;
  simulateToDirectory(c, dir.path());
  EXPECT_EQ(std::filesystem::exists(dir.path() / "radar.geometry"), v.resolution_m != 0.0432);
  const auto reader = openDataset(dir.path());
  ASSERT_EQ(reader->size(), 2u);
  const auto scan = reader->readScan(1);
  EXPECT_EQ(scan->num_azimuths, 400u);
  EXPECT_EQ(scan->num_bins, static_cast<std::uint32_t>(v.bins));
  EXPECT_DOUBLE_EQ(scan->range_resolution_m, v.resolution_m);
  EXPECT_DOUBLE_EQ(scan->range_offset_m, v.resolution_m / 2);
  EXPECT_NEAR(scan->maxRange(), v.bins * v.resolution_m + v.resolution_m / 2, 1e-9);
  // The RAS6 alternates up/down chirps; the flag travels through byte 10 of the PNG rows.
  const bool alternating = std::string(v.config) == "sim_boreas.yaml";
  EXPECT_EQ(c.geometry.chirp, alternating ? "alternating" : "single");
  EXPECT_EQ(scan->hasChirpDirections(), alternating);
  if (alternating) {
    EXPECT_EQ(scan->chirp(0), 1);
    EXPECT_EQ(scan->chirp(1), -1);
    EXPECT_EQ(scan->chirp(399), -1);
    EXPECT_EQ(std::count(scan->azimuth_valid.begin(), scan->azimuth_valid.end(), 1), 400);
  }
  // Something is seen, and the Cartesian image (scan's own geometry) is not empty.
  PolarToCartesian cart(CartesianParams{.size_px = 201, .m_per_px = 1.0});
  EXPECT_GT(cv::countNonZero(cart.convert(*scan)), 1000);
}

INSTANTIATE_TEST_SUITE_P(Navtech, SensorVariant,
                         ::testing::Values(Variant{"sim.yaml", 3768, 0.0432},
                                           Variant{"sim_mulran.yaml", 3360, 0.05952},
                                           Variant{"sim_boreas.yaml", 6848, 0.04381}),
                         [](const ::testing::TestParamInfo<Variant>& p) {
                           const std::string name = p.param.config;
                           return name.substr(0, name.find('.'));
                         });
