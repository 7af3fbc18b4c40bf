#include "radarslam/radar/doppler_compensation.h"

#include <cmath>
#include <string>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, DopplerParams& params) {
  yaml.get("enabled", params.enabled);
  yaml.get("beta_s", params.beta_s, Range::closed(-1, 1));
}

double dopplerRangeOffset(double beta_s, int s, const BodyVelocity& v, double phi) {
  return static_cast<double>(s) * beta_s * (v.vx * std::cos(phi) + v.vy * std::sin(phi));
}

void compensateDoppler(CObservationRadarScan& scan, const BodyVelocity& v, double beta_s) {
  if (beta_s == 0.0 || (v.vx == 0.0 && v.vy == 0.0)) return;
  if (scan.azimuth_angles_rad.size() != scan.num_azimuths || !(scan.range_resolution_m > 0.0) ||
      scan.power.size() != static_cast<std::size_t>(scan.num_azimuths) * scan.num_bins)
    throw InputError("radar scan", "Doppler compensation needs a consistent scan");
  const auto n = static_cast<std::ptrdiff_t>(scan.num_bins);
  std::vector<std::uint8_t> src(scan.num_bins);
  for (std::size_t a = 0; a < scan.num_azimuths; ++a) {
    // Bin k (true range r_k) was measured at r_k - offset, i.e. at fractional source bin k - shift.
    const double shift = dopplerRangeOffset(beta_s, chirpSign(scan, a), v, scan.azimuth_angles_rad[a]) /
                         scan.range_resolution_m;
    if (std::abs(shift) < 1e-6) continue;
    const auto row = scan.row(a);
    std::copy(row.begin(), row.end(), src.begin());
    const double fl = std::floor(shift);
    const auto whole = static_cast<std::ptrdiff_t>(fl);
    const double w1 = shift - fl;  // weight of source bin (k - whole - 1)
    const double w0 = 1.0 - w1;    // weight of source bin (k - whole)
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      const std::ptrdiff_t i0 = k - whole, i1 = i0 - 1;
      const double p0 = i0 >= 0 && i0 < n ? src[static_cast<std::size_t>(i0)] : 0.0;
      const double p1 = i1 >= 0 && i1 < n ? src[static_cast<std::size_t>(i1)] : 0.0;
      row[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(std::lround(w0 * p0 + w1 * p1));
    }
  }
}

void compensateDoppler(std::span<RadarPoint> points, const CObservationRadarScan& scan, const BodyVelocity& v,
                       double beta_s) {
  if (beta_s == 0.0) return;
  for (RadarPoint& p : points) {
    if (p.azimuth >= scan.num_azimuths || p.azimuth >= scan.azimuth_angles_rad.size())
      throw InputError("radar scan", "point azimuth " + std::to_string(p.azimuth) + " is not in a scan of " +
                                         std::to_string(scan.num_azimuths) + " azimuths");
    const double phi = scan.azimuth_angles_rad[p.azimuth];
    const double r =
        static_cast<double>(p.range_m) + dopplerRangeOffset(beta_s, chirpSign(scan, p.azimuth), v, phi);
    p.range_m = static_cast<float>(r);
    p.x = static_cast<float>(r * std::cos(phi));
    p.y = static_cast<float>(r * std::sin(phi));
  }
}

}  // namespace radarslam
