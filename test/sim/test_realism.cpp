// Realism is measured: simulated scans at Oxford geometry vs the real Oxford scans, with explicit
// tolerances on intensity statistics (docs/simulator.md lists the current numbers).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "radarslam/io/dataset.h"
#include "radarslam/sim/scan_statistics.h"
#include "radarslam/sim/simulator.h"
#include "shared_data.h"

using namespace radarslam;
using namespace radarslam::sim;

TEST(SimStatistics, MeasuresFloorContrastAndBrightBins) {
  CObservationRadarScan s;
  s.resize(10, 1000);
  s.range_resolution_m = 0.1;
  for (std::size_t a = 0; a < 10; ++a)
    for (std::size_t b = 0; b < 1000; ++b) s.row(a)[b] = (b % 10 == 0) ? 60 : 6;  // 10 % bright
  StatisticsParams p;
  p.bands = 2, p.min_range_m = 0;
  const auto st = computeScanStatistics(s, p);
  ASSERT_EQ(st.bands.size(), 2u);
  EXPECT_EQ(st.bands[0].floor, 6);
  EXPECT_NEAR(st.bands[0].bright_fraction, 0.1, 1e-9);
  EXPECT_NEAR(st.bands[0].mean, 11.4, 1e-9);
  EXPECT_NEAR(st.bands[0].contrast, std::sqrt(0.1 * 60 * 60 + 0.9 * 36 - 11.4 * 11.4) / 11.4, 1e-9);
  EXPECT_NEAR(st.histogram[60], 0.1, 1e-9);
  EXPECT_DOUBLE_EQ(histogramDistance(st.histogram, st.histogram), 0.0);
  auto shifted = st.histogram;
  shifted.fill(0);
  shifted[9] = 0.9, shifted[63] = 0.1;  // everything 3 codes up
  EXPECT_NEAR(histogramDistance(st.histogram, shifted), 3.0, 1e-9);
}

TEST(SimRealism, SimulatedScansMatchRealOxfordStatistics) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  const auto reader = openDataset(dir);
  std::vector<ScanStatistics> real_stats, sim_stats;
  for (std::size_t i = 0; i < reader->size(); ++i)
    real_stats.push_back(computeScanStatistics(*reader->readScan(i)));
  SimulationConfig c;                             // Oxford geometry by default
  constexpr std::size_t kFirst = 60, kCount = 6;  // scans while driving through the city
  c.scans = kFirst + kCount;
  Simulation sim(c);
  CObservationRadarScan s;
  for (std::size_t i = kFirst; i < kFirst + kCount; ++i) {
    sim.render(i, s);
    sim_stats.push_back(computeScanStatistics(s));
  }
  const auto real = averageStatistics(real_stats), simulated = averageStatistics(sim_stats);
  std::cout << compareStatisticsTable(real, simulated);
  // Overall intensity distribution: mean absolute CDF difference below 2.2 codes (~dB).
  EXPECT_LT(histogramDistance(real.histogram, simulated.histogram), 2.2);
  EXPECT_NEAR(simulated.zero_fraction, real.zero_fraction, 0.08);
  // Bright bins (>= 10 dB over the band's floor): overall within a factor of 1.6.
  EXPECT_GT(simulated.bright_fraction, real.bright_fraction / 1.6);
  EXPECT_LT(simulated.bright_fraction, real.bright_fraction * 1.6);
  ASSERT_EQ(real.bands.size(), simulated.bands.size());
  for (std::size_t k = 0; k < real.bands.size(); ++k) {
    const auto &r = real.bands[k], &m = simulated.bands[k];
    EXPECT_NEAR(m.floor, r.floor, 5.0) << "band " << k;        // noise floor within 5 dB
    EXPECT_NEAR(m.contrast, r.contrast, 0.3) << "band " << k;  // speckle contrast
    EXPECT_GT(m.bright_fraction, r.bright_fraction / 3) << "band " << k;
    EXPECT_LT(m.bright_fraction, r.bright_fraction * 3) << "band " << k;
  }
}
