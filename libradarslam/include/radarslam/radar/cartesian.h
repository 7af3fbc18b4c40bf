#pragma once
// Polar -> Cartesian radar image (paper Sec. II, eq. (1)), bilinear, with the Oxford SDK's axes:
// the image centre is the sensor, image rows run along -x (top row = +x, forward) and image
// columns along +y. A pixel (row, col) is at x = (c_row - row) * m_per_px,
// y = (col - c_col) * m_per_px with c_row = (rows - 1) / 2 and c_col = (cols - 1) / 2
// (for the usual square image c_row = c_col = (size_px - 1) / 2).
//
// A pixel's value is the bilinear interpolation of the polar image at its azimuth angle
// atan2(y, x) and range hypot(x, y): along range between the two nearest bins (bin k at
// range_offset_m + k * range_resolution_m), along azimuth between the two azimuths whose own
// angles (CObservationRadarScan::azimuth_angles_rad, not an assumed uniform spacing) bracket the
// pixel's angle, including across the wrap from the last azimuth back to the first. Pixels
// outside the sampled range [bin 0, last bin] are 0.
#include <opencv2/core/mat.hpp>

#include <memory>
#include <mutex>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

class YamlParams;

struct CartesianParams {
  int size_px = 701;       ///< image side (RadarSLAM: 701 px covering +-87.5 m); the width; valid [16, 4096]
  double m_per_px = 0.25;  ///< metres per pixel; valid [0.01, 10]
  int height_px = 0;       ///< image rows; 0 = size_px (square); valid [0, 4096]
  /// Convert the remap tables to OpenCV's fixed-point form (1/32 px sub-steps): ~2x faster
  /// remap, interpolation weights quantised to 1/32.
  bool fixed_point_maps = true;

  int rows() const { return height_px > 0 ? height_px : size_px; }
  int cols() const { return size_px; }
};

/// Overrides `params` from the keys size_px, m_per_px, height_px, fixed_point_maps of `yaml`.
void loadParams(const YamlParams& yaml, CartesianParams& params);

class PolarToCartesian {
 public:
  /// Throws InputError("CartesianParams", ...) for a non-positive size or resolution.
  explicit PolarToCartesian(const CartesianParams& params = {});
  ~PolarToCartesian();

  /// CV_8UC1 rows() x cols(). Uses the scan's own per-azimuth angles; the remap tables are
  /// cached and rebuilt only when the scan geometry (sizes, range resolution/offset, angles)
  /// changes. Thread-safe. Throws InputError if the scan is inconsistent.
  cv::Mat convert(const CObservationRadarScan& scan) const;
  /// As above, writing into `out` (reallocated only if its size/type differ).
  void convert(const CObservationRadarScan& scan, cv::Mat& out) const;

  const CartesianParams& params() const { return params_; }
  cv::Point2f metresToPixel(double x, double y) const;      ///< (col, row) as cv::Point2f(x=col, y=row)
  cv::Point2d pixelToMetres(double col, double row) const;  ///< (x, y) in the sensor frame

  /// How many times the remap tables were (re)built (for tests and diagnostics).
  std::size_t tableBuilds() const;

 private:
  struct Tables;
  std::shared_ptr<const Tables> tablesFor(const CObservationRadarScan& scan) const;

  CartesianParams params_;
  mutable std::mutex mutex_;
  mutable std::shared_ptr<const Tables> tables_;
  mutable std::size_t builds_ = 0;
};

}  // namespace radarslam
