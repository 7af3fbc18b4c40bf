#pragma once
// Private to the scan statistics (scan_, realism_, streak_statistics.cpp): the range bin where a
// band of ranges starts or ends, so every statistic counts the same bins for the same band.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::sim::detail {

/// The first bin whose range is at or beyond `range_m` (bin b lies at range_offset_m + b ×
/// range_resolution_m), clamped to [0, num_bins].
inline std::size_t firstBinAtOrBeyond(const CObservationRadarScan& scan, double range_m) {
  const double b = std::ceil((range_m - scan.range_offset_m) / scan.range_resolution_m);
  return static_cast<std::size_t>(std::clamp(b, 0.0, static_cast<double>(scan.num_bins)));
}

}  // namespace radarslam::sim::detail
