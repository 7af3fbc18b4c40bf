#pragma once
// The probabilistic point cloud of RadarSLAM (paper Sec. III-C, Algorithm 1): per azimuth, find
// peaks with a minimum prominence and a minimum distance between them, and keep the peaks whose
// power is >= mean + 1 std of that azimuth's peak powers. Used for loop closure (M2DP) and ICP.
//
// Details fixed here (the paper leaves them open):
//  - findPeaks is radar/find_peaks.h (MATLAB/scipy definitions of prominence and distance),
//    run on the bins inside [min_range_m, max_range_m] only, so near-range clutter neither
//    yields peaks nor acts as a base for their prominence.
//  - sigma is the population standard deviation (N normalisation). With N - 1 (MATLAB's std
//    default) an azimuth with exactly two peaks could never keep either (the higher one is only
//    1/sqrt(2) sigma above the mean); with N it keeps the higher one. A single peak is kept.
//    As in the paper, an azimuth whose top peaks tie (e.g. several saturated at 255 plus lower
//    ones) can have mu + sigma above every peak and keep nothing; this never happened on the
//    4400 azimuths of the Oxford tiny sample with the default parameters (measured).
//  - A point is at range range_offset_m + bin * range_resolution_m along its azimuth's own angle.
#include <cstdint>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

class YamlParams;

struct PeakCloudParams {
  double min_peak_prominence = 20.0;  ///< delta_p, power units (0..255); valid [0, 255]
  int min_peak_distance_bins = 20;    ///< delta_d, bins; valid [1, 10000]
  double min_range_m = 2.5;           ///< ignore near-range clutter; valid [0, 1000]
  double max_range_m = 0.0;           ///< 0 = full range; valid [0, 10000]
  /// Box-filter each azimuth over this many bins (odd; <= 1 = off) before findPeaks; the points'
  /// power is then the smoothed power. Off by default: see the measurement in peak_cloud.cpp.
  int smoothing_bins = 0;  ///< valid [0, 1000]
};

/// Overrides `params` from the keys min_peak_prominence, min_peak_distance_bins, min_range_m,
/// max_range_m, smoothing_bins of `yaml`.
void loadParams(const YamlParams& yaml, PeakCloudParams& params);

struct RadarPoint {
  float x = 0.f, y = 0.f;  ///< metres, sensor frame
  float range_m = 0.f;
  float power = 0.f;          ///< 0..255
  std::uint32_t azimuth = 0;  ///< row index in the scan (gives the firing time)
};

std::vector<RadarPoint> extractPeakCloud(const CObservationRadarScan& scan,
                                         const PeakCloudParams& params = {});

/// First and one-past-last bin whose range lies in [min_range_m, max_range_m] (max 0 = no limit).
std::pair<std::uint32_t, std::uint32_t> binWindow(const CObservationRadarScan& scan, double min_range_m,
                                                  double max_range_m);

}  // namespace radarslam
