// PolarToCartesian: axes, bilinear interpolation along range and azimuth, the azimuth wrap,
// image sizes, the range limit, the table cache and thread safety.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>

#include <opencv2/core.hpp>

#include <radarslam/core/errors.h>
#include <radarslam/core/yaml_params.h>
#include <radarslam/radar/cartesian.h>

#include "synthetic_scan.h"

namespace radarslam {
namespace {

using test::makeScan;

class CartesianBothMaps : public ::testing::TestWithParam<bool> {
 protected:
  CartesianParams params(int size, double m_per_px, int height = 0) const {
    CartesianParams p;
    p.size_px = size;
    p.m_per_px = m_per_px;
    p.height_px = height;
    p.fixed_point_maps = GetParam();
    return p;
  }
  // cv::remap quantises bilinear weights to 1/32 (with float maps too), then rounds to 8 bits.
  double tolerance(double span) const { return span / 32.0 + 0.6; }
};

cv::Point maxLoc(const cv::Mat& img) {
  cv::Point loc;
  cv::minMaxLoc(img, nullptr, nullptr, nullptr, &loc);
  return loc;
}

TEST_P(CartesianBothMaps, BrightBinAtAzimuthZeroIsStraightUp) {
  auto scan = makeScan(400, 1000, 0.1);
  scan.row(0)[200] = 255;  // azimuth 0 (angle 0 = +x), range 20 m
  const PolarToCartesian conv(params(201, 0.25));
  const cv::Mat img = conv.convert(scan);
  ASSERT_EQ(img.type(), CV_8UC1);
  ASSERT_EQ(img.rows, 201);
  ASSERT_EQ(img.cols, 201);
  const int c = 100, d = 80;  // R / m_per_px
  EXPECT_EQ(img.at<std::uint8_t>(c - d, c), 255);
  EXPECT_EQ(maxLoc(img), cv::Point(c, c - d));     // cv::Point(x = col, y = row)
  EXPECT_EQ(cv::countNonZero(img.row(c + d)), 0);  // nothing behind the sensor
  const cv::Point2f px = conv.metresToPixel(20.0, 0.0);
  EXPECT_FLOAT_EQ(px.x, c);
  EXPECT_FLOAT_EQ(px.y, c - d);
}

TEST_P(CartesianBothMaps, BrightBinAtAzimuth90DegreesIsRight) {
  auto scan = makeScan(400, 1000, 0.1);
  scan.row(100)[200] = 255;  // azimuth 100 of 400 = 90 deg (+y), range 20 m
  const PolarToCartesian conv(params(201, 0.25));
  const cv::Mat img = conv.convert(scan);
  const int c = 100, d = 80;
  EXPECT_EQ(img.at<std::uint8_t>(c, c + d), 255);
  EXPECT_EQ(maxLoc(img), cv::Point(c + d, c));
  const cv::Point2d m = conv.pixelToMetres(c + d, c);
  EXPECT_NEAR(m.x, 0.0, 1e-12);
  EXPECT_NEAR(m.y, 20.0, 1e-12);
}

TEST_P(CartesianBothMaps, BilinearHalfwayBetweenTwoBins) {
  auto scan = makeScan(400, 1000, 0.1);
  scan.row(0)[200] = 200;                           // 20.0 m
  scan.row(0)[201] = 100;                           // 20.1 m
  const PolarToCartesian conv(params(1001, 0.05));  // a pixel every 5 cm along +x
  const cv::Mat img = conv.convert(scan);
  const int c = 500;
  EXPECT_EQ(img.at<std::uint8_t>(c - 400, c), 200);                    // 20.00 m
  EXPECT_NEAR(img.at<std::uint8_t>(c - 401, c), 150, tolerance(100));  // 20.05 m: halfway
  EXPECT_EQ(img.at<std::uint8_t>(c - 402, c), 100);                    // 20.10 m
}

TEST_P(CartesianBothMaps, BilinearBetweenAzimuthsAndAcrossTheWrap) {
  auto scan = makeScan(400, 1000, 0.1);
  std::fill(scan.row(0).begin(), scan.row(0).end(), 100);
  std::fill(scan.row(1).begin(), scan.row(1).end(), 200);
  std::fill(scan.row(399).begin(), scan.row(399).end(), 40);  // angle -0.9 deg, wraps to row 0
  const PolarToCartesian conv(params(401, 0.25));
  const cv::Mat img = conv.convert(scan);
  const double step = 2.0 * std::numbers::pi / 400;
  int checked_between = 0, checked_wrap = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int col = 0; col < img.cols; ++col) {
      const cv::Point2d p = conv.pixelToMetres(col, r);
      const double range = std::hypot(p.x, p.y), angle = std::atan2(p.y, p.x);
      if (range < 5.0 || range > 45.0) continue;
      if (angle > 0.0 && angle < step) {  // between azimuths 0 and 1
        const double t = angle / step;
        EXPECT_NEAR(img.at<std::uint8_t>(r, col), 100 * (1 - t) + 200 * t, tolerance(100)) << r << "," << col;
        ++checked_between;
      } else if (angle < 0.0 && angle > -step) {  // between azimuth 399 and (wrapped) azimuth 0
        const double t = (angle + step) / step;
        EXPECT_NEAR(img.at<std::uint8_t>(r, col), 40 * (1 - t) + 100 * t, tolerance(60)) << r << "," << col;
        ++checked_wrap;
      }
    }
  EXPECT_GT(checked_between, 20);
  EXPECT_GT(checked_wrap, 20);
}

TEST_P(CartesianBothMaps, UsesTheScansOwnAnglesWhateverTheFiringOrder) {
  // Same sweep fired starting at 180 deg with a non-uniform wobble: the image must not depend on
  // the row order, only on each row's angle.
  auto a = makeScan(360, 600, 0.2);
  for (std::uint32_t i = 0; i < 360; ++i) {
    a.azimuth_angles_rad[i] = (i + 0.3 * std::sin(i)) * std::numbers::pi / 180.0;
    for (std::uint32_t k = 0; k < 600; ++k) a.row(i)[k] = static_cast<std::uint8_t>((i * 7 + k * 13) % 251);
  }
  auto b = a;
  for (std::uint32_t i = 0; i < 360; ++i) {
    const std::uint32_t src = (i + 180) % 360;
    b.azimuth_angles_rad[i] = a.azimuth_angles_rad[src] + (src < 180 ? 2.0 * std::numbers::pi : 0.0);
    std::copy(a.row(src).begin(), a.row(src).end(), b.row(i).begin());
  }
  const PolarToCartesian conv(params(301, 0.5));
  const cv::Mat ia = conv.convert(a), ib = conv.convert(b);
  EXPECT_LE(cv::norm(ia, ib, cv::NORM_INF), 1.0);  // wrapped angles may differ by an ulp
  EXPECT_GT(cv::countNonZero(ia), 301 * 301 / 2);
}

TEST_P(CartesianBothMaps, NonSquareAndEvenSizes) {
  auto scan = makeScan(400, 1000, 0.1);
  // Returns 1 m long in range, so that they cannot fall between pixel centres 0.25 m apart.
  for (int k = -5; k <= 5; ++k) {
    scan.row(0)[200 + k] = 255;    // (20, 0)
    scan.row(100)[150 + k] = 255;  // (0, 15)
  }
  for (const auto& [w, h] :
       {std::pair{301, 200}, std::pair{200, 301}, std::pair{250, 250}, std::pair{151, 171}}) {
    const PolarToCartesian conv(params(w, 0.25, h));
    const cv::Mat img = conv.convert(scan);
    ASSERT_EQ(img.cols, w);
    ASSERT_EQ(img.rows, h);
    for (const auto& [x, y] : {std::pair{20.0, 0.0}, std::pair{0.0, 15.0}}) {
      const cv::Point2f px = conv.metresToPixel(x, y);
      const cv::Point2d back = conv.pixelToMetres(px.x, px.y);
      EXPECT_NEAR(back.x, x, 1e-5);
      EXPECT_NEAR(back.y, y, 1e-5);
      // The return's intensity centroid is where metresToPixel says (even sizes put the image
      // centre between pixels; the returns are symmetric about their nominal point).
      double sum = 0, sum_col = 0, sum_row = 0;
      for (int r = std::max(0, int(px.y) - 8); r <= std::min(h - 1, int(px.y) + 8); ++r)
        for (int col = std::max(0, int(px.x) - 8); col <= std::min(w - 1, int(px.x) + 8); ++col) {
          const double v = img.at<std::uint8_t>(r, col);
          sum += v;
          sum_col += v * col;
          sum_row += v * r;
        }
      ASSERT_GE(sum, 2 * 255) << w << "x" << h;
      EXPECT_NEAR(sum_col / sum, px.x, 0.2) << w << "x" << h << " at " << x << "," << y;
      EXPECT_NEAR(sum_row / sum, px.y, 0.2) << w << "x" << h << " at " << x << "," << y;
    }
  }
}

TEST_P(CartesianBothMaps, ZeroBeyondTheLastBin) {
  auto scan = makeScan(400, 300, 0.1, 0.05);  // bins at 0.05 .. 29.95 m
  std::fill(scan.power.begin(), scan.power.end(), 255);
  const PolarToCartesian conv(params(301, 0.25));  // covers +-37.5 m
  const cv::Mat img = conv.convert(scan);
  for (int r = 0; r < img.rows; ++r)
    for (int col = 0; col < img.cols; ++col) {
      const cv::Point2d p = conv.pixelToMetres(col, r);
      const double range = std::hypot(p.x, p.y);
      if (range > 29.95 + 1e-6) {
        ASSERT_EQ(img.at<std::uint8_t>(r, col), 0) << range;
      } else if (range > 0.05 + 1e-6) {
        ASSERT_EQ(img.at<std::uint8_t>(r, col), 255) << range;
      }
    }
}

INSTANTIATE_TEST_SUITE_P(FloatAndFixedPoint, CartesianBothMaps, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) {
                           return p.param ? "fixed_point" : "float";
                         });

TEST(Cartesian, TablesAreCachedPerGeometryAndAngles) {
  auto scan = makeScan(400, 500, 0.1);
  const PolarToCartesian conv(CartesianParams{101, 0.5});
  conv.convert(scan);
  conv.convert(scan);
  EXPECT_EQ(conv.tableBuilds(), 1u);
  scan.row(3)[40] = 9;  // new data, same geometry
  conv.convert(scan);
  EXPECT_EQ(conv.tableBuilds(), 1u);
  scan.azimuth_angles_rad[7] += 1e-4;  // angles changed
  conv.convert(scan);
  EXPECT_EQ(conv.tableBuilds(), 2u);
  scan.range_resolution_m = 0.2;
  conv.convert(scan);
  EXPECT_EQ(conv.tableBuilds(), 3u);
}

TEST(Cartesian, ConcurrentConversionsAgree) {
  auto a = makeScan(400, 500, 0.1), b = makeScan(400, 500, 0.12);
  for (std::size_t i = 0; i < a.power.size(); ++i) {
    a.power[i] = static_cast<std::uint8_t>(i * 31 % 256);
    b.power[i] = static_cast<std::uint8_t>(i * 17 % 256);
  }
  const PolarToCartesian conv(CartesianParams{151, 0.4});
  const cv::Mat ref_a = PolarToCartesian(CartesianParams{151, 0.4}).convert(a);
  const cv::Mat ref_b = PolarToCartesian(CartesianParams{151, 0.4}).convert(b);
  std::vector<std::thread> threads;
  std::vector<int> mismatches(4, 0);
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int k = 0; k < 20; ++k) {  // alternating geometries force rebuilds while others read
        const bool use_a = (k + t) % 2 == 0;
        const cv::Mat img = conv.convert(use_a ? a : b);
        if (cv::norm(img, use_a ? ref_a : ref_b, cv::NORM_INF) != 0.0) ++mismatches[t];
      }
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

TEST(Cartesian, ParamsFromYaml) {
  CartesianParams p;
  const auto yaml = YamlParams::fromText("size_px: 1000\nm_per_px: 0.2\nfixed_point_maps: false\n");
  loadParams(yaml, p);
  EXPECT_EQ(p.size_px, 1000);
  EXPECT_DOUBLE_EQ(p.m_per_px, 0.2);
  EXPECT_FALSE(p.fixed_point_maps);
  EXPECT_EQ(p.rows(), 1000);  // height defaults to the width
  EXPECT_NO_THROW(yaml.rejectUnknownKeys());
  EXPECT_THROW(loadParams(YamlParams::fromText("size_px: big\n"), p), InputError);
}

TEST(Cartesian, RejectsBadParamsAndScans) {
  EXPECT_THROW(PolarToCartesian(CartesianParams{0, 0.25}), InputError);
  EXPECT_THROW(PolarToCartesian(CartesianParams{100, 0.0}), InputError);
  auto scan = makeScan(10, 10);
  scan.power.pop_back();
  EXPECT_THROW(PolarToCartesian().convert(scan), InputError);
}

}  // namespace
}  // namespace radarslam
