#pragma once
// Saturation streaks of polar radar scans (issue 13, realism; docs/simulator.md "Saturation
// streaks"): a streak is an azimuth lit along its whole range, fixed to the sensor, which the
// per-band statistics of realism_statistics.h barely see. An azimuth counts as a streak of at
// least T codes when its median code over [min_m, max_m) exceeds the median of the azimuths
// `neighbour_min`..`neighbour_max` steps either side of it by >= T. Narrow by construction: a
// sector lit by the scene (a street opening, a near facade) wider than the neighbour offsets
// lifts the neighbours too.
#include <array>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::sim {

struct StreakParams {
  double min_m = 20;      ///< range band the azimuth's median is taken over; valid [0, max_m)
  double max_m = 160;     ///< valid (min_m, inf)
  int neighbour_min = 3;  ///< neighbours compared with: these offsets on each side; valid [1, neighbour_max]
  int neighbour_max = 5;  ///< valid [neighbour_min, azimuths / 2)
};

/// The thresholds reported, in codes above the neighbours (codes are ~dB of power).
inline constexpr std::array<int, 3> kStreakThresholdsCodes{6, 10, 15};

struct StreakFractions {
  /// Fraction of azimuths that are streaks of at least kStreakThresholdsCodes[i] codes.
  std::array<double, kStreakThresholdsCodes.size()> fraction{};
  std::size_t azimuths = 0;
};

/// Throws InputError("StreakParams", ...) for an invalid band or neighbourhood.
StreakFractions computeStreakFractions(const CObservationRadarScan& scan, const StreakParams& params = {});

/// Azimuth-weighted mean over scans.
StreakFractions averageStreaks(const std::vector<StreakFractions>& scans);

}  // namespace radarslam::sim
