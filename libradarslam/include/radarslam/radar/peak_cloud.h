#pragma once
// The probabilistic point cloud of RadarSLAM (paper Sec. III-C, Algorithm 1): per azimuth, find
// peaks with a minimum prominence and a minimum distance between them, and keep the peaks whose
// power is >= mean + 1 std of that azimuth's peak powers. Used for loop closure (M2DP) and ICP.
#include <cstdint>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

struct PeakCloudParams {
  double min_peak_prominence = 20.0;  ///< delta_p, power units (0..255)
  int min_peak_distance_bins = 20;    ///< delta_d, bins
  double min_range_m = 2.5;           ///< ignore near-range clutter
  double max_range_m = 0.0;           ///< 0 = full range
};

struct RadarPoint {
  float x = 0.f, y = 0.f;     ///< metres, sensor frame
  float range_m = 0.f;
  float power = 0.f;          ///< 0..255
  std::uint32_t azimuth = 0;  ///< row index in the scan (gives the firing time)
};

std::vector<RadarPoint> extractPeakCloud(const CObservationRadarScan& scan, const PeakCloudParams& params = {});

}  // namespace radarslam
