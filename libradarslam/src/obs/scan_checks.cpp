#include "radarslam/obs/scan_checks.h"

#include <sstream>

namespace radarslam {

std::string checkScanPlausible(const CObservationRadarScan& scan, const ScanLimits& limits) {
  if (std::string why = scan.checkConsistency(); !why.empty()) return why;
  std::ostringstream why;
  if (scan.num_azimuths < limits.min_azimuths)
    why << scan.num_azimuths << " azimuths (a sweep needs >= " << limits.min_azimuths << ")";
  else if (scan.num_bins < limits.min_bins)
    why << scan.num_bins << " range bins (a scan needs >= " << limits.min_bins << ")";
  else if (scan.range_resolution_m > limits.max_range_resolution_m)
    why << "range resolution " << scan.range_resolution_m << " m is implausible (> "
        << limits.max_range_resolution_m << " m)";
  else if (scan.range_offset_m > limits.max_abs_range_offset_m ||
           scan.range_offset_m < -limits.max_abs_range_offset_m)
    why << "range offset " << scan.range_offset_m << " m is implausible (beyond +-"
        << limits.max_abs_range_offset_m << " m)";
  if (!why.str().empty()) return why.str();
  const auto& t = scan.azimuth_stamps_ns;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < limits.min_stamp_ns) {
      why << "azimuth " << i << " stamp " << t[i] << " ns is not a UNIX time";
      return why.str();
    }
    if (i > 0 && t[i] < t[i - 1]) {
      why << "azimuth " << i << " stamp goes backwards (" << t[i] << " ns after " << t[i - 1] << " ns)";
      return why.str();
    }
  }
  if (t.back() - t.front() > limits.max_sweep_ns)
    why << "sweep lasts " << toSeconds(t.back() - t.front()) << " s (corrupt azimuth stamps?)";
  return why.str();
}

}  // namespace radarslam
