#include "radarslam/radar/cartesian.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double wrapTwoPi(double a) {
  double w = std::fmod(a, kTwoPi);
  if (w < 0.0) w += kTwoPi;
  return w >= kTwoPi ? 0.0 : w;
}

}  // namespace

// Range bin coordinate and angle of every pixel; depends on the image and the range geometry only.
struct PixelPolar {
  int num_bins = 0;
  double resolution = 0.0, offset = 0.0;
  cv::Mat bin;    // CV_32F, fractional bin index, or -1 outside [0, num_bins - 1]
  cv::Mat angle;  // CV_32F, atan2(y, x) in (-pi, pi]
};

struct PolarToCartesian::Tables {
  // Cache key: the scan geometry the tables were built for.
  std::uint32_t num_azimuths = 0, num_bins = 0;
  double resolution = 0.0, offset = 0.0;
  std::vector<double> angles;

  std::shared_ptr<const PixelPolar> pixels;
  std::vector<std::uint32_t> order;  // scan row of the i-th azimuth in increasing wrapped angle
  cv::Mat map1, map2;                // cv::remap tables into the angle-sorted, wrap-padded image

  bool matches(const CObservationRadarScan& s) const {
    return num_azimuths == s.num_azimuths && num_bins == s.num_bins && resolution == s.range_resolution_m &&
           offset == s.range_offset_m && angles == s.azimuth_angles_rad;
  }
};

void loadParams(const YamlParams& yaml, CartesianParams& params) {
  yaml.get("size_px", params.size_px, Range::closed(16, 4096));
  yaml.get("m_per_px", params.m_per_px, Range::closed(0.01, 10));
  yaml.get("height_px", params.height_px, Range::closed(0, 4096));
  yaml.get("fixed_point_maps", params.fixed_point_maps);
}

PolarToCartesian::PolarToCartesian(const CartesianParams& params) : params_(params) {
  if (params_.size_px <= 0 || params_.height_px < 0)
    throw InputError("CartesianParams", "image size must be > 0 (size_px " + std::to_string(params_.size_px) +
                                            ", height_px " + std::to_string(params_.height_px) + ")");
  if (!(params_.m_per_px > 0.0) || !std::isfinite(params_.m_per_px))
    throw InputError("CartesianParams",
                     "m_per_px must be > 0 (got " + std::to_string(params_.m_per_px) + ")");
}

PolarToCartesian::~PolarToCartesian() = default;

cv::Point2f PolarToCartesian::metresToPixel(double x, double y) const {
  const double c_row = (params_.rows() - 1) / 2.0, c_col = (params_.cols() - 1) / 2.0;
  return {static_cast<float>(c_col + y / params_.m_per_px), static_cast<float>(c_row - x / params_.m_per_px)};
}

cv::Point2d PolarToCartesian::pixelToMetres(double col, double row) const {
  const double c_row = (params_.rows() - 1) / 2.0, c_col = (params_.cols() - 1) / 2.0;
  return {(c_row - row) * params_.m_per_px, (col - c_col) * params_.m_per_px};
}

std::size_t PolarToCartesian::tableBuilds() const {
  std::lock_guard lock(mutex_);
  return builds_;
}

std::shared_ptr<const PolarToCartesian::Tables> PolarToCartesian::tablesFor(
    const CObservationRadarScan& scan) const {
  std::lock_guard lock(mutex_);
  if (tables_ && tables_->matches(scan)) return tables_;

  auto t = std::make_shared<Tables>();
  t->num_azimuths = scan.num_azimuths;
  t->num_bins = scan.num_bins;
  t->resolution = scan.range_resolution_m;
  t->offset = scan.range_offset_m;
  t->angles = scan.azimuth_angles_rad;

  // Per-pixel range and angle: reused when only the azimuth angles change (e.g. Boreas wobble).
  if (tables_ && tables_->pixels->num_bins == static_cast<int>(scan.num_bins) &&
      tables_->pixels->resolution == scan.range_resolution_m &&
      tables_->pixels->offset == scan.range_offset_m) {
    t->pixels = tables_->pixels;
  } else {
    auto px = std::make_shared<PixelPolar>();
    px->num_bins = static_cast<int>(scan.num_bins);
    px->resolution = scan.range_resolution_m;
    px->offset = scan.range_offset_m;
    const int rows = params_.rows(), cols = params_.cols();
    px->bin.create(rows, cols, CV_32F);
    px->angle.create(rows, cols, CV_32F);
    const double last_bin = scan.num_bins - 1.0;
    for (int r = 0; r < rows; ++r) {
      auto* bin = px->bin.ptr<float>(r);
      auto* ang = px->angle.ptr<float>(r);
      for (int c = 0; c < cols; ++c) {
        const cv::Point2d p = pixelToMetres(c, r);
        const double b = (std::hypot(p.x, p.y) - scan.range_offset_m) / scan.range_resolution_m;
        bin[c] = (b >= 0.0 && b <= last_bin) ? static_cast<float>(b) : -1.f;
        ang[c] = static_cast<float>(std::atan2(p.y, p.x));
      }
    }
    t->pixels = std::move(px);
  }

  // Azimuths sorted by wrapped angle; the padded image repeats the first sorted azimuth at
  // angle + 2 pi so that interpolation across the wrap is an ordinary bilinear step.
  const std::size_t n = scan.num_azimuths;
  std::vector<double> wrapped(n);
  for (std::size_t i = 0; i < n; ++i) wrapped[i] = wrapTwoPi(scan.azimuth_angles_rad[i]);
  t->order.resize(n);
  std::iota(t->order.begin(), t->order.end(), 0u);
  std::stable_sort(t->order.begin(), t->order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return wrapped[a] < wrapped[b]; });
  std::vector<double> sorted(n + 1);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = wrapped[t->order[i]];
  const double a0 = sorted[0];
  sorted[n] = a0 + kTwoPi;

  const int rows = params_.rows(), cols = params_.cols();
  cv::Mat map_bin(rows, cols, CV_32F), map_row(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r) {
    const auto* bin = t->pixels->bin.ptr<float>(r);
    const auto* ang = t->pixels->angle.ptr<float>(r);
    auto* mb = map_bin.ptr<float>(r);
    auto* mr = map_row.ptr<float>(r);
    for (int c = 0; c < cols; ++c) {
      if (bin[c] < 0.f) {  // outside the sampled range: fully outside the source image -> 0
        mb[c] = -2.f;
        mr[c] = -2.f;
        continue;
      }
      const double a = a0 + wrapTwoPi(static_cast<double>(ang[c]) - a0);  // in [a0, a0 + 2 pi)
      const auto it = std::upper_bound(sorted.begin(), sorted.end(), a);
      const std::size_t j = std::min<std::size_t>(static_cast<std::size_t>(it - sorted.begin()), n) - 1;
      const double gap = sorted[j + 1] - sorted[j];
      const double frac = gap > 0.0 ? std::clamp((a - sorted[j]) / gap, 0.0, 1.0) : 0.0;
      mb[c] = bin[c];
      mr[c] = static_cast<float>(j + frac);
    }
  }
  if (params_.fixed_point_maps) {
    cv::convertMaps(map_bin, map_row, t->map1, t->map2, CV_16SC2, false);
  } else {
    t->map1 = map_bin;
    t->map2 = map_row;
  }
  tables_ = std::move(t);
  ++builds_;
  return tables_;
}

void PolarToCartesian::convert(const CObservationRadarScan& scan, cv::Mat& out) const {
  if (const std::string problem = scan.checkConsistency(); !problem.empty())
    throw InputError(scan.sensorLabel.empty() ? std::string("radar scan") : scan.sensorLabel,
                     "cannot convert to Cartesian: " + problem);
  const auto tables = tablesFor(scan);

  // Angle-sorted polar image plus the wrap row (a copy of the first sorted azimuth).
  thread_local cv::Mat padded;
  const int n = static_cast<int>(scan.num_azimuths), bins = static_cast<int>(scan.num_bins);
  padded.create(n + 1, bins, CV_8U);
  for (int i = 0; i <= n; ++i) {
    const auto src = scan.row(tables->order[static_cast<std::size_t>(i % n)]);
    std::copy(src.begin(), src.end(), padded.ptr<std::uint8_t>(i));
  }
  cv::remap(padded, out, tables->map1, tables->map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
}

cv::Mat PolarToCartesian::convert(const CObservationRadarScan& scan) const {
  cv::Mat out;
  convert(scan, out);
  return out;
}

}  // namespace radarslam
