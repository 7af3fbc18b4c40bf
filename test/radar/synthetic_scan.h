#pragma once
// Small synthetic polar scans for the radar module's tests.
#include <cstdint>
#include <numbers>

#include <radarslam/obs/CObservationRadarScan.h>

namespace radarslam::test {

/// All-zero scan: `azimuths` uniform angles 2 pi i / azimuths, bin k at offset + k * res,
/// azimuth i fired at t0 + i * 625 us (a 4 Hz sweep of 400 azimuths).
inline CObservationRadarScan makeScan(std::uint32_t azimuths, std::uint32_t bins, double res = 0.1,
                                      double offset = 0.0, StampNs t0 = 1'500'000'000'000'000'000) {
  CObservationRadarScan s;
  s.resize(azimuths, bins);
  s.range_resolution_m = res;
  s.range_offset_m = offset;
  for (std::uint32_t i = 0; i < azimuths; ++i)
    s.azimuth_stamps_ns[i] = t0 + static_cast<StampNs>(i) * 625'000;
  s.updateReferenceTime();
  return s;
}

}  // namespace radarslam::test
