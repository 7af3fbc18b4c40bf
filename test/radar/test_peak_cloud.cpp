// extractPeakCloud (Algorithm 1): mean + 1 sigma selection, geometry of the points, range window.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <radarslam/core/errors.h>
#include <radarslam/core/yaml_params.h>
#include <radarslam/radar/peak_cloud.h>

#include "synthetic_scan.h"

namespace radarslam {
namespace {

using test::makeScan;

// A narrow triangular return (prominence = height on a zero background).
void addReturn(CObservationRadarScan& scan, std::uint32_t azimuth, std::uint32_t bin, std::uint8_t power) {
  auto row = scan.row(azimuth);
  row[bin] = power;
  row[bin - 1] = static_cast<std::uint8_t>(power / 2);
  row[bin + 1] = static_cast<std::uint8_t>(power / 2);
}

TEST(PeakCloud, KeepsPeaksAtLeastOneSigmaAboveTheMean) {
  auto scan = makeScan(8, 1000, 0.1);
  const std::vector<std::pair<std::uint32_t, std::uint8_t>> returns = {{100, 50},  {200, 60},  {300, 70},
                                                                       {400, 200}, {500, 190}, {600, 40}};
  for (const auto& [bin, power] : returns) addReturn(scan, 3, bin, power);
  PeakCloudParams params;
  params.min_peak_prominence = 10;
  params.min_peak_distance_bins = 20;
  params.min_range_m = 0.0;
  const auto cloud = extractPeakCloud(scan, params);

  // mu and (population) sigma of the six powers, computed independently.
  double mu = 0, ss = 0;
  for (const auto& r : returns) mu += r.second;
  mu /= returns.size();
  for (const auto& r : returns) ss += (r.second - mu) * (r.second - mu);
  const double threshold = mu + std::sqrt(ss / returns.size());  // 101.7 + 66.7
  std::vector<std::uint32_t> want;
  for (const auto& [bin, power] : returns)
    if (power >= threshold) want.push_back(bin);
  ASSERT_EQ(want, (std::vector<std::uint32_t>{400, 500}));  // 200 and 190 only

  ASSERT_EQ(cloud.size(), want.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(cloud[i].azimuth, 3u);
    EXPECT_NEAR(cloud[i].range_m, want[i] * 0.1, 1e-5);
  }
  EXPECT_FLOAT_EQ(cloud[0].power, 200);
  EXPECT_FLOAT_EQ(cloud[1].power, 190);
}

TEST(PeakCloud, SinglePeakIsKeptAndDistanceSuppressionApplies) {
  auto scan = makeScan(4, 500, 0.1);
  addReturn(scan, 0, 100, 80);
  addReturn(scan, 1, 100, 80);
  addReturn(scan, 1, 110, 120);  // 10 bins from the first: suppresses it with delta_d = 20
  PeakCloudParams params;
  params.min_range_m = 0.0;
  params.min_peak_prominence = 10;
  params.min_peak_distance_bins = 20;
  const auto cloud = extractPeakCloud(scan, params);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud[0].azimuth, 0u);  // alone in its azimuth: sigma = 0, kept
  EXPECT_EQ(cloud[1].azimuth, 1u);
  EXPECT_NEAR(cloud[1].range_m, 11.0, 1e-5);
  EXPECT_FLOAT_EQ(cloud[1].power, 120);

  // Now both peaks of azimuth 1 survive findPeaks; mu + sigma = 100 + 20 keeps only 120.
  params.min_peak_distance_bins = 5;
  const auto cloud2 = extractPeakCloud(scan, params);
  ASSERT_EQ(cloud2.size(), 2u);
  EXPECT_EQ(cloud2[1].azimuth, 1u);
  EXPECT_NEAR(cloud2[1].range_m, 11.0, 1e-5);

  params.min_peak_prominence = 100;  // 80 is no longer a peak at all
  const auto cloud3 = extractPeakCloud(scan, params);
  ASSERT_EQ(cloud3.size(), 1u);
  EXPECT_EQ(cloud3[0].azimuth, 1u);
}

TEST(PeakCloud, PointsLieAlongTheirAzimuthsAngle) {
  auto scan = makeScan(400, 1000, 0.05, 0.025);
  for (std::uint32_t a = 0; a < 400; a += 25) {
    scan.azimuth_angles_rad[a] += 0.001 * a;  // non-uniform angles must be honoured
    addReturn(scan, a, 200 + a, 150);
  }
  PeakCloudParams params;
  params.min_range_m = 0.0;
  const auto cloud = extractPeakCloud(scan, params);
  ASSERT_EQ(cloud.size(), 16u);
  for (const RadarPoint& p : cloud) {
    const double r = 0.025 + (200 + p.azimuth) * 0.05;
    const double angle = scan.azimuth_angles_rad[p.azimuth];
    EXPECT_NEAR(p.range_m, r, 1e-4);
    EXPECT_NEAR(p.x, r * std::cos(angle), 1e-4);
    EXPECT_NEAR(p.y, r * std::sin(angle), 1e-4);
  }
  // Azimuth 100 of 400 is +y.
  const auto it =
      std::find_if(cloud.begin(), cloud.end(), [](const RadarPoint& p) { return p.azimuth == 100; });
  ASSERT_NE(it, cloud.end());
  EXPECT_GT(it->y, 10.0);
}

TEST(PeakCloud, HonoursTheRangeWindow) {
  auto scan = makeScan(2, 1000, 0.1);  // bin k at k * 0.1 m
  addReturn(scan, 0, 20, 200);         // 2.0 m
  addReturn(scan, 0, 300, 200);        // 30 m
  addReturn(scan, 0, 800, 200);        // 80 m
  PeakCloudParams params;
  params.min_range_m = 2.5;
  params.max_range_m = 50.0;
  const auto cloud = extractPeakCloud(scan, params);
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_NEAR(cloud[0].range_m, 30.0, 1e-5);
  params.min_range_m = 0.0;
  params.max_range_m = 0.0;
  EXPECT_EQ(extractPeakCloud(scan, params).size(), 3u);

  EXPECT_EQ(binWindow(scan, 2.5, 50.0), (std::pair<std::uint32_t, std::uint32_t>{25, 501}));
  EXPECT_EQ(binWindow(scan, 0.0, 0.0), (std::pair<std::uint32_t, std::uint32_t>{0, 1000}));
  EXPECT_EQ(binWindow(scan, 500.0, 0.0).second - binWindow(scan, 500.0, 0.0).first, 0u);
}

TEST(PeakCloud, SmoothingMergesASplitReturn) {
  auto scan = makeScan(1, 400, 0.1);
  auto row = scan.row(0);
  for (std::uint32_t k = 0; k < 400; ++k) row[k] = static_cast<std::uint8_t>(k % 2 ? 10 : 0);  // speckle
  const std::uint8_t split[] = {60, 140, 60, 140, 60};  // one target, dip in the middle
  std::copy(std::begin(split), std::end(split), row.begin() + 200);
  PeakCloudParams params;
  params.min_range_m = 0.0;
  params.min_peak_prominence = 30;
  params.min_peak_distance_bins = 1;
  const auto raw = extractPeakCloud(scan, params);
  ASSERT_EQ(raw.size(), 2u);  // bins 201 and 203
  EXPECT_NEAR(raw[0].range_m, 20.1, 1e-5);
  EXPECT_NEAR(raw[1].range_m, 20.3, 1e-5);
  params.smoothing_bins = 3;
  const auto smooth = extractPeakCloud(scan, params);
  ASSERT_EQ(smooth.size(), 1u);  // smoothed: 86.7, 113.3, 86.7 -> one peak in the middle
  EXPECT_NEAR(smooth[0].range_m, 20.2, 1e-5);
  EXPECT_NEAR(smooth[0].power, (140 + 60 + 140) / 3.0, 1e-3);
}

TEST(PeakCloud, ParamsFromYaml) {
  PeakCloudParams p;
  const auto yaml =
      YamlParams::fromText("min_peak_prominence: 12.5\nmin_peak_distance_bins: 7\nmax_range_m: 80\n");
  loadParams(yaml, p);
  EXPECT_DOUBLE_EQ(p.min_peak_prominence, 12.5);
  EXPECT_EQ(p.min_peak_distance_bins, 7);
  EXPECT_DOUBLE_EQ(p.max_range_m, 80.0);
  EXPECT_DOUBLE_EQ(p.min_range_m, 2.5);  // default kept
  EXPECT_NO_THROW(yaml.rejectUnknownKeys());
}

}  // namespace
}  // namespace radarslam
