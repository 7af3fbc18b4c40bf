#pragma once
// 1-D peak finding with a minimum prominence and a minimum distance, defined as MATLAB's
// findpeaks (MinPeakProminence, MinPeakDistance) and scipy.signal.find_peaks define them; used
// per azimuth by Algorithm 1 of the paper (radar/peak_cloud.h).
//
//  - A peak is a sample strictly higher than its neighbours; for a flat top (plateau) bounded by
//    lower samples on both sides the peak is the plateau's middle sample (scipy; the left of two
//    middles). The first and last samples are never peaks.
//  - Prominence: the peak's height above the higher of its two bases. The left base is the
//    minimum of the signal between the peak and the nearest sample to its left that is strictly
//    higher than the peak (or the signal start); the right base likewise.
//  - Peaks below the minimum prominence are dropped first (MATLAB's order), then the distance
//    rule: taking the remaining peaks from the highest down (ties: lower index first), each kept
//    peak removes all lower-priority peaks closer than `min_distance` samples (so kept peaks are
//    >= min_distance apart, scipy's definition; MATLAB drops peaks at distance <= MinPeakDistance).
//
// Cost O(n + k log k) for n samples and k peaks: one pass reduces the signal to its turning points,
// monotonic-stack passes over those give every base (no per-peak scans).
#include <cstdint>
#include <span>
#include <vector>

namespace radarslam {

struct FindPeaksParams {
  double min_prominence = 0.0;  ///< keep peaks with prominence >= this
  int min_distance = 1;         ///< kept peaks are at least this many samples apart (<= 1: no rule)
};

struct Peak {
  std::uint32_t index = 0;  ///< sample index in the signal
  float height = 0.f;       ///< signal value at the peak
  float prominence = 0.f;
};

/// Peaks of `signal` in increasing index order. Reuses `out`'s storage.
void findPeaks(std::span<const std::uint8_t> signal, const FindPeaksParams& params, std::vector<Peak>& out);
void findPeaks(std::span<const float> signal, const FindPeaksParams& params, std::vector<Peak>& out);

inline std::vector<Peak> findPeaks(std::span<const std::uint8_t> signal, const FindPeaksParams& params = {}) {
  std::vector<Peak> out;
  findPeaks(signal, params, out);
  return out;
}
inline std::vector<Peak> findPeaks(std::span<const float> signal, const FindPeaksParams& params = {}) {
  std::vector<Peak> out;
  findPeaks(signal, params, out);
  return out;
}

}  // namespace radarslam
