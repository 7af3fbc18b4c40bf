#include "radarslam/sim/streak_statistics.h"

#include <algorithm>
#include <vector>

#include "radarslam/core/errors.h"
#include "range_bins.h"

namespace radarslam::sim {

StreakFractions computeStreakFractions(const CObservationRadarScan& scan, const StreakParams& p) {
  const std::size_t A = scan.num_azimuths;
  if (!(p.min_m >= 0 && p.max_m > p.min_m) || p.neighbour_min < 1 || p.neighbour_max < p.neighbour_min ||
      2 * static_cast<std::size_t>(p.neighbour_max) >= A)
    throw InputError("StreakParams",
                     "needs 0 <= min_m < max_m and 1 <= neighbour_min <= neighbour_max < azimuths / 2");
  const std::size_t b0 = detail::firstBinAtOrBeyond(scan, p.min_m);
  const std::size_t b1 = detail::firstBinAtOrBeyond(scan, p.max_m);
  StreakFractions out;
  out.azimuths = A;
  if (b1 <= b0) return out;  // the band is beyond the scan's range
  std::vector<int> median(A);
  std::vector<std::uint8_t> codes;
  for (std::size_t a = 0; a < A; ++a) {
    const auto row = scan.row(a);
    codes.assign(row.begin() + static_cast<std::ptrdiff_t>(b0),
                 row.begin() + static_cast<std::ptrdiff_t>(b1));
    const auto mid = codes.begin() + static_cast<std::ptrdiff_t>(codes.size() / 2);
    std::nth_element(codes.begin(), mid, codes.end());
    median[a] = *mid;
  }
  std::vector<int> around;
  for (std::size_t a = 0; a < A; ++a) {
    around.clear();
    for (int k = p.neighbour_min; k <= p.neighbour_max; ++k) {
      around.push_back(median[(a + static_cast<std::size_t>(k)) % A]);
      around.push_back(median[(a + A - static_cast<std::size_t>(k)) % A]);
    }
    const auto mid = around.begin() + static_cast<std::ptrdiff_t>(around.size() / 2);
    std::nth_element(around.begin(), mid, around.end());
    const int excess = median[a] - *mid;
    for (std::size_t t = 0; t < kStreakThresholdsCodes.size(); ++t)
      if (excess >= kStreakThresholdsCodes[t]) out.fraction[t] += 1.0;
  }
  for (double& f : out.fraction) f /= static_cast<double>(A);
  return out;
}

StreakFractions averageStreaks(const std::vector<StreakFractions>& scans) {
  StreakFractions out;
  for (const auto& s : scans) {
    for (std::size_t t = 0; t < out.fraction.size(); ++t)
      out.fraction[t] += s.fraction[t] * static_cast<double>(s.azimuths);
    out.azimuths += s.azimuths;
  }
  if (out.azimuths > 0)
    for (double& f : out.fraction) f /= static_cast<double>(out.azimuths);
  return out;
}

}  // namespace radarslam::sim
