// The radar module on real Oxford Radar RobotCar scans (../shared, never copied into the repo):
// the Cartesian image matches an independent bilinear evaluation of the polar scan, and the
// Algorithm-1 cloud is a small, high-power subset of the naive local maxima.
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include <radarslam/io/dataset.h>
#include <radarslam/obs/registration.h>
#include <radarslam/radar/cartesian.h>
#include <radarslam/radar/find_peaks.h>
#include <radarslam/radar/peak_cloud.h>

#include "shared_data.h"

namespace radarslam {
namespace {

// Bilinear value of the polar scan at (range, angle), written independently of PolarToCartesian
// for a scan with uniformly increasing angles (Oxford): azimuth i at angle_0 + i * step.
double polarBilinear(const CObservationRadarScan& s, double range, double angle) {
  const std::size_t n = s.num_azimuths;
  const double a0 = s.azimuth_angles_rad[0];
  const double step = (s.azimuth_angles_rad[n - 1] - a0) / static_cast<double>(n - 1);
  double u = std::fmod(angle - a0, 2.0 * std::numbers::pi);
  if (u < 0) u += 2.0 * std::numbers::pi;
  const double fa = u / step;
  const auto i0 = static_cast<std::size_t>(fa) % n, i1 = (i0 + 1) % n;
  const double ta = fa - std::floor(fa);
  const double fb = (range - s.range_offset_m) / s.range_resolution_m;
  const auto k0 = static_cast<std::size_t>(fb);
  const double tb = fb - static_cast<double>(k0);
  auto at = [&](std::size_t i, std::size_t k) { return static_cast<double>(s.row(i)[k]); };
  const double v0 = at(i0, k0) * (1 - tb) + at(i0, k0 + 1) * tb;
  const double v1 = at(i1, k0) * (1 - tb) + at(i1, k0 + 1) * tb;
  return v0 * (1 - ta) + v1 * ta;
}

TEST(RealOxford, CartesianMatchesTheScan) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  registerRadarslamClasses();
  const auto reader = openDataset(dir);
  ASSERT_GE(reader->size(), 2u);
  const auto scan = reader->readScan(0);
  ASSERT_EQ(scan->num_azimuths, 400u);
  ASSERT_EQ(scan->num_bins, 3768u);

  for (const bool fixed : {true, false}) {
    CartesianParams params;  // 701 x 701 at 0.25 m/px
    params.fixed_point_maps = fixed;
    const PolarToCartesian conv(params);
    const cv::Mat img = conv.convert(*scan);
    ASSERT_EQ(img.size(), cv::Size(701, 701));

    // Plausible content: most pixels lit by speckle, a bright minority (structure).
    const double lit = cv::countNonZero(img) / (701.0 * 701.0);
    EXPECT_GT(lit, 0.5);
    cv::Scalar mean, stddev;
    cv::meanStdDev(img, mean, stddev);
    EXPECT_GT(mean[0], 3.0);
    EXPECT_LT(mean[0], 60.0);
    EXPECT_GT(stddev[0], 5.0);

    // Random pixels agree with the independent bilinear evaluation (remap's 1/32 weights).
    std::mt19937 rng(1);
    int checked = 0;
    double worst = 0;
    for (int t = 0; t < 3000; ++t) {
      const int r = static_cast<int>(rng() % 701), c = static_cast<int>(rng() % 701);
      const cv::Point2d p = conv.pixelToMetres(c, r);
      const double range = std::hypot(p.x, p.y);
      if (range < 1.0) continue;
      const double want = polarBilinear(*scan, range, std::atan2(p.y, p.x));
      const double err = std::abs(img.at<std::uint8_t>(r, c) - want);
      worst = std::max(worst, err);
      EXPECT_LE(err, 255.0 / 32.0 + 1.0) << "pixel " << r << "," << c;  // remap weights step 1/32
      ++checked;
    }
    double mean_err = 0;  // on average the error is small
    for (int t = 0; t < 3000; ++t) {
      const int r = static_cast<int>(rng() % 701), c = static_cast<int>(rng() % 701);
      const cv::Point2d p = conv.pixelToMetres(c, r);
      if (std::hypot(p.x, p.y) < 1.0) continue;
      mean_err += std::abs(img.at<std::uint8_t>(r, c) -
                           polarBilinear(*scan, std::hypot(p.x, p.y), std::atan2(p.y, p.x)));
    }
    EXPECT_LT(mean_err / 3000.0, 0.8);
    EXPECT_GT(checked, 2500);
    RecordProperty(fixed ? "worst_err_fixed" : "worst_err_float", std::to_string(worst));
  }
}

TEST(RealOxford, PeakCloudIsASmallHighPowerSubsetOfTheLocalMaxima) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  registerRadarslamClasses();
  const auto reader = openDataset(dir);
  const PeakCloudParams params;
  for (std::size_t i = 0; i < reader->size(); i += 5) {
    const auto scan = reader->readScan(i);
    const auto [lo, hi] = binWindow(*scan, params.min_range_m, params.max_range_m);
    std::size_t naive = 0;
    double naive_power = 0;
    for (std::uint32_t a = 0; a < scan->num_azimuths; ++a)
      for (const Peak& p : findPeaks(scan->row(a).subspan(lo, hi - lo))) {  // every local maximum
        ++naive;
        naive_power += p.height;
      }
    const auto cloud = extractPeakCloud(*scan, params);
    double cloud_power = 0;
    for (const RadarPoint& p : cloud) {
      cloud_power += p.power;
      ASSERT_GE(p.range_m, params.min_range_m);
      ASSERT_LE(p.range_m, scan->maxRange());
    }
    SCOPED_TRACE("scan " + std::to_string(i));
    EXPECT_GT(cloud.size(), 300u);        // structure is found ...
    EXPECT_LT(cloud.size() * 10, naive);  // ... in far fewer points than the speckle maxima
    EXPECT_GT(cloud_power / cloud.size(), 3.0 * naive_power / naive);  // and much brighter ones
  }
}

}  // namespace
}  // namespace radarslam
