#pragma once
// One sweep of a 360° spinning FMCW radar (Navtech CTS350-X, CIR204-H, RAS6) as an MRPT
// observation, so scans travel through MRPT's rawlogs and tools like any other sensor.
//
// Polar power image: `num_azimuths` rows (one per firing direction, in firing order) by
// `num_bins` range bins, 8-bit power. Bin k is at range  range_offset_m + k * range_resolution_m
// (Oxford: offset = res/2, bin centres; Boreas: offset = -0.31 m).
//
// Angles: azimuth angle in radians in the sensor frame, 0 along the sensor's +x axis and
// increasing towards +y (the Oxford SDK convention: x forward, y right for a z-down radar).
//
// Chirp direction (`azimuth_chirp`): +1 up-chirp, -1 down-chirp, 0 unknown or a single-chirp
// sensor (CTS350-X, CIR204-H). The RAS6 (Boreas-RT) alternates up and down chirps between
// consecutive azimuths (byte 10 of its rows: 255 / 0); the FMCW Doppler range offset has opposite
// signs for the two (radar/doppler_compensation.h). Empty = unknown for every azimuth.
//
// Reference time (`timestamp`, and refStampNs()): the midpoint between the first and the last
// azimuth's timestamps. Ground truth poses and estimated poses of a scan are given at this time;
// motion compensation expresses every azimuth's returns in the sensor frame at this time.
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdint>
#include <span>
#include <vector>

#include "radarslam/core/time.h"

namespace radarslam {

class CObservationRadarScan : public mrpt::obs::CObservation {
  DEFINE_SERIALIZABLE(CObservationRadarScan, radarslam)

 public:
  // --- geometry -------------------------------------------------------------------------
  std::uint32_t num_azimuths = 0;
  std::uint32_t num_bins = 0;
  double range_resolution_m = 0.0;
  double range_offset_m = 0.0;

  // --- data (row-major num_azimuths x num_bins) --------------------------------------------
  std::vector<std::uint8_t> power;
  std::vector<StampNs> azimuth_stamps_ns;   ///< per azimuth, ns UNIX
  std::vector<double> azimuth_angles_rad;   ///< per azimuth, see the angle convention above
  std::vector<std::uint8_t> azimuth_valid;  ///< 1 = genuine reading, 0 = interpolated/unknown
  std::vector<std::int8_t> azimuth_chirp;   ///< per azimuth +1 up / -1 down / 0 unknown; or empty

  /// Pose of the radar on the vehicle (identity when poses are given for the radar itself).
  mrpt::poses::CPose3D sensorPose;

  /// Allocates an all-zero scan with the given geometry (angles uniform, all valid, stamps 0,
  /// chirp unknown).
  void resize(std::uint32_t azimuths, std::uint32_t bins);

  std::span<const std::uint8_t> row(std::size_t azimuth) const {
    return {power.data() + azimuth * num_bins, num_bins};
  }
  std::span<std::uint8_t> row(std::size_t azimuth) { return {power.data() + azimuth * num_bins, num_bins}; }
  double binRange(std::size_t bin) const {
    return range_offset_m + static_cast<double>(bin) * range_resolution_m;
  }
  double maxRange() const { return binRange(num_bins); }
  /// Chirp direction of an azimuth (+1 up, -1 down, 0 unknown / single chirp).
  int chirp(std::size_t azimuth) const { return azimuth < azimuth_chirp.size() ? azimuth_chirp[azimuth] : 0; }
  /// True if any azimuth has a known chirp direction.
  bool hasChirpDirections() const;

  /// Midpoint of the first and last azimuth stamps (the scan's reference time, see above).
  StampNs refStampNs() const;
  /// Sets `timestamp` from refStampNs().
  void updateReferenceTime();

  /// Empty string if consistent; otherwise the first problem (sizes, non-finite values, ...).
  std::string checkConsistency() const;

  // mrpt::obs::CObservation
  void getSensorPose(mrpt::poses::CPose3D& out_sensorPose) const override { out_sensorPose = sensorPose; }
  void setSensorPose(const mrpt::poses::CPose3D& newSensorPose) override { sensorPose = newSensorPose; }
  void getDescriptionAsText(std::ostream& o) const override;
};

}  // namespace radarslam
