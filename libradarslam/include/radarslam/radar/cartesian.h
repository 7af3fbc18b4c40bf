#pragma once
// Polar -> Cartesian radar image (paper Sec. II, eq. (1)), bilinear, with the Oxford SDK's axes:
// the image centre is the sensor, image rows run along -x (top row = +x, forward) and image
// columns along +y. A pixel (row, col) is at x = (c - row) * m_per_px, y = (col - c) * m_per_px
// with c = (size_px - 1) / 2.
#include <opencv2/core/mat.hpp>

#include <mutex>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

struct CartesianParams {
  int size_px = 701;        ///< square image side (RadarSLAM: 701 px covering +-87.5 m)
  double m_per_px = 0.25;   ///< metres per pixel
};

class PolarToCartesian {
 public:
  explicit PolarToCartesian(const CartesianParams& params = {});

  /// CV_8UC1 size_px x size_px. Uses the scan's own per-azimuth angles; the remap tables are
  /// cached and rebuilt only when the scan geometry changes. Thread-safe.
  cv::Mat convert(const CObservationRadarScan& scan) const;

  const CartesianParams& params() const { return params_; }
  cv::Point2f metresToPixel(double x, double y) const;  ///< (col, row) as cv::Point2f(x=col, y=row)
  cv::Point2d pixelToMetres(double col, double row) const;  ///< (x, y) in the sensor frame

 private:
  CartesianParams params_;
  // Cache keyed by geometry (num_azimuths, num_bins, resolution, offset, angles hash).
  mutable std::mutex mutex_;
  mutable std::size_t cache_key_ = 0;
  mutable cv::Mat map_azimuth_, map_bin_;
};

}  // namespace radarslam
