#pragma once
// Intensity statistics of a polar radar scan, to measure how close simulated scans are to real
// ones (not claim it): the 8-bit power histogram and, per range band, the noise floor (median),
// speckle contrast (std/mean) and the fraction of bright bins (a margin above the band's floor;
// the Navtech code is ~1 unit per dB of power, so the margin is in dB-equivalent).
#include <array>
#include <string>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::sim {

struct StatisticsParams {
  int bands = 6;                   ///< equal range bands from min_range_m to the scan's max range
  double min_range_m = 3.0;        ///< skip the housing/near-range clutter
  double bright_margin_db = 10.0;  ///< "bright" = code >= band floor + margin
};

struct BandStatistics {
  double range_min_m = 0, range_max_m = 0;
  double floor = 0;  ///< median code
  double mean = 0, stddev = 0;
  double contrast = 0;  ///< stddev / mean
  double bright_fraction = 0;
};

struct ScanStatistics {
  std::array<double, 256> histogram{};  ///< normalised to sum 1 (bins past min_range_m)
  std::vector<BandStatistics> bands;
  double bright_fraction = 0;  ///< over all bands
  double zero_fraction = 0;    ///< code 0 (amplitude below the 8-bit step)
};

ScanStatistics computeScanStatistics(const CObservationRadarScan& scan, const StatisticsParams& params = {});

/// Mean of several scans' statistics (band by band; same geometry assumed).
ScanStatistics averageStatistics(const std::vector<ScanStatistics>& stats);

/// Earth mover's distance between two normalised histograms, in code units.
double histogramDistance(const std::array<double, 256>& a, const std::array<double, 256>& b);

/// A table "band | floor | contrast | bright" for real vs simulated, for reports and logs.
std::string compareStatisticsTable(const ScanStatistics& real, const ScanStatistics& sim);

}  // namespace radarslam::sim
