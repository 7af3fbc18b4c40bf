#pragma once
// Plausibility rules for a radar scan from outside (a live DDS sample; docs/dds.md), the same
// rules the polar-image file readers enforce while decoding (io/polar_png.cpp): consistent sizes
// and finite values (CObservationRadarScan::checkConsistency), a geometry a spinning radar can
// have, and azimuth stamps that are UNIX times, never go backwards and span at most 10 s.
#include <cstdint>
#include <string>

#include "radarslam/core/time.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

struct ScanLimits {
  /// Fewer azimuths or bins cannot be a 360-degree sweep (real sensors: 400 x 576..6848).
  std::uint32_t min_azimuths = 16;
  std::uint32_t min_bins = 16;
  double max_range_resolution_m = 10.0;  ///< real sensors: 0.04..0.18 m
  double max_abs_range_offset_m = 1000.0;
  /// Azimuth stamps before this are not a sensor's UNIX time (1973-03-03, as the PNG readers).
  StampNs min_stamp_ns = 100'000'000'000'000'000LL;
  StampNs max_sweep_ns = 10 * kNsPerSec;
};

/// Empty if `scan` passes every rule, otherwise the first problem (one line, no file name).
std::string checkScanPlausible(const CObservationRadarScan& scan, const ScanLimits& limits = {});

}  // namespace radarslam
