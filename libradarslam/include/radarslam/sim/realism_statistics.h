#pragma once
// Per-range-band realism statistics of polar radar scans, and their real-vs-simulated comparison
// (issue 13). Everything is measured on the 8-bit codes as stored, per band [r0, r1) of range:
//  - median code, zero fraction (code 0), bright fraction (code >= bright_code), 99th percentile;
//  - Algorithm-1 peak density: points of the project's own Algorithm 1 (radar/peak_cloud.h, its
//    default parameters unless told otherwise) whose range falls in the band, per azimuth per 10 m;
//  - speckle contrast std/mean of the codes;
//  - range / azimuth correlation length: the lag at which the normalised autocovariance of the
//    codes (mean removed per azimuth-band segment / per bin column) first drops below 1/e,
//    linearly interpolated between lags; in metres along range and in degrees along azimuth.
#include <string>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam::sim {

struct RealismBand {
  double min_m = 0, max_m = 0;
};

/// The reviewer's four bands: 2-10, 10-40, 40-80, 80-160 m.
std::vector<RealismBand> defaultRealismBands();

struct RealismParams {
  std::vector<RealismBand> bands = defaultRealismBands();
  int bright_code = 60;      ///< "bright" = code >= this; valid [1, 255]
  int max_range_lag = 200;   ///< bins searched for the range correlation length; valid [1, 10000]
  int max_azimuth_lag = 50;  ///< azimuths searched for the azimuth correlation length; valid [1, 1000]
  PeakCloudParams peaks;     ///< Algorithm 1 (defaults = the project's)
};

/// The statistics, in the order of kRealismNames.
enum RealismStat {
  kMedian,
  kZeroFraction,
  kBrightFraction,
  kP99,
  kPeakDensity,
  kContrast,
  kRangeCorrM,
  kAzimuthCorrDeg,
  kRealismStatCount
};
extern const char* const kRealismNames[kRealismStatCount];

struct RealismBandStats {
  RealismBand band;
  double value[kRealismStatCount] = {};
};

struct RealismStatistics {
  std::vector<RealismBandStats> bands;
};

RealismStatistics computeRealismStatistics(const CObservationRadarScan& scan,
                                           const RealismParams& params = {});

/// Mean over scans, statistic by statistic and band by band (same bands assumed).
RealismStatistics averageRealism(const std::vector<RealismStatistics>& stats);

/// "Within x`factor`" for one statistic: real and sim within the factor of each other, or both
/// below the statistic's absolute floor (realismAbsoluteFloor: a ratio of two near-zero values is
/// noise), or their difference below that floor.
bool realismWithin(RealismStat stat, double real, double sim, double factor = 1.5);

/// Below this absolute difference two values count as equal (fractions: 0.001; peak density:
/// 0.01 per azimuth per 10 m; codes: 1; contrast: 0.02; correlation lengths: half a bin / step).
double realismAbsoluteFloor(RealismStat stat);

struct RealismComparison {
  std::string table;  ///< band | statistic | real | sim | ratio | within
  int checked = 0, within = 0;
};

RealismComparison compareRealism(const RealismStatistics& real, const RealismStatistics& sim,
                                 double factor = 1.5);

}  // namespace radarslam::sim
