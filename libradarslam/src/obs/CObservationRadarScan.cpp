#include "radarslam/obs/CObservationRadarScan.h"

#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <sstream>

IMPLEMENTS_SERIALIZABLE(CObservationRadarScan, mrpt::obs::CObservation, radarslam)

namespace radarslam {

namespace {
// Guards against absurd sizes in corrupt archives before allocating (RAS6 has 6848 bins).
constexpr std::uint32_t kMaxAzimuths = 1u << 14;
constexpr std::uint32_t kMaxBins = 1u << 16;
// Found by fuzzing (docs/hardening.md): corrupt sizes must fail before a huge allocation.
constexpr std::uint64_t kMaxCells = 1u << 26;       // 16x the largest real scan (400 x 6848)
constexpr std::uint32_t kMaxLabelBytes = 1u << 12;  // MRPT's string reader trusts any uint32 length
}  // namespace

void CObservationRadarScan::resize(std::uint32_t azimuths, std::uint32_t bins) {
  num_azimuths = azimuths;
  num_bins = bins;
  power.assign(static_cast<std::size_t>(azimuths) * bins, 0);
  azimuth_stamps_ns.assign(azimuths, 0);
  azimuth_angles_rad.resize(azimuths);
  for (std::uint32_t i = 0; i < azimuths; ++i)
    azimuth_angles_rad[i] = 2.0 * std::numbers::pi * i / std::max<std::uint32_t>(azimuths, 1);
  azimuth_valid.assign(azimuths, 1);
  azimuth_chirp.assign(azimuths, 0);
}

bool CObservationRadarScan::hasChirpDirections() const {
  return std::any_of(azimuth_chirp.begin(), azimuth_chirp.end(), [](std::int8_t c) { return c != 0; });
}

StampNs CObservationRadarScan::refStampNs() const {
  if (azimuth_stamps_ns.empty()) return 0;
  // Halve each term first: no int64 overflow for any real stamp.
  return azimuth_stamps_ns.front() / 2 + azimuth_stamps_ns.back() / 2 +
         (azimuth_stamps_ns.front() % 2 + azimuth_stamps_ns.back() % 2) / 2;
}

void CObservationRadarScan::updateReferenceTime() { timestamp = toMrptTime(refStampNs()); }

std::string CObservationRadarScan::checkConsistency() const {
  std::ostringstream why;
  if (num_azimuths == 0 || num_bins == 0)
    why << "empty scan (" << num_azimuths << "x" << num_bins << ")";
  else if (num_azimuths > kMaxAzimuths || num_bins > kMaxBins)
    why << "implausible size " << num_azimuths << "x" << num_bins;
  else if (power.size() != static_cast<std::size_t>(num_azimuths) * num_bins)
    why << "power has " << power.size() << " cells, expected " << num_azimuths << "x" << num_bins;
  else if (azimuth_stamps_ns.size() != num_azimuths || azimuth_angles_rad.size() != num_azimuths ||
           azimuth_valid.size() != num_azimuths)
    why << "per-azimuth arrays do not have " << num_azimuths << " entries";
  else if (!azimuth_chirp.empty() && azimuth_chirp.size() != num_azimuths)
    why << "azimuth_chirp has " << azimuth_chirp.size() << " entries, expected 0 or " << num_azimuths;
  else if (std::any_of(azimuth_chirp.begin(), azimuth_chirp.end(),
                       [](std::int8_t c) { return c < -1 || c > 1; }))
    why << "azimuth_chirp values must be -1, 0 or +1";
  else if (!(range_resolution_m > 0.0) || !std::isfinite(range_resolution_m))
    why << "range resolution must be > 0 (got " << range_resolution_m << ")";
  else if (!std::isfinite(range_offset_m))
    why << "range offset is not finite";
  else {
    for (std::size_t i = 0; i < num_azimuths; ++i)
      if (!std::isfinite(azimuth_angles_rad[i])) {
        why << "azimuth " << i << " angle is not finite";
        break;
      }
  }
  return why.str();
}

void CObservationRadarScan::getDescriptionAsText(std::ostream& o) const {
  CObservation::getDescriptionAsText(o);
  o << "Radar scan: " << num_azimuths << " azimuths x " << num_bins << " bins, " << range_resolution_m
    << " m/bin, range offset " << range_offset_m << " m, max range " << maxRange() << " m\n";
  if (!azimuth_stamps_ns.empty())
    o << "Sweep: first azimuth " << azimuth_stamps_ns.front() << " ns, last " << azimuth_stamps_ns.back()
      << " ns, reference (mid) " << refStampNs() << " ns\n";
  o << "Sensor pose on vehicle: " << sensorPose << "\n";
}

// Version 0 layout: label, timestamp, sensor pose, geometry, per-azimuth arrays, power.
// Version 1 appends the chirp directions: uint8 1 + num_azimuths int8 values, or uint8 0 when
// unknown for every azimuth. Version 0 archives read as "chirp unknown".
uint8_t CObservationRadarScan::serializeGetVersion() const { return 1; }

void CObservationRadarScan::serializeTo(mrpt::serialization::CArchive& out) const {
  out << sensorLabel << timestamp << sensorPose;
  out << num_azimuths << num_bins << range_resolution_m << range_offset_m;
  out.WriteBufferFixEndianness(azimuth_stamps_ns.data(), azimuth_stamps_ns.size());
  out.WriteBufferFixEndianness(azimuth_angles_rad.data(), azimuth_angles_rad.size());
  out.WriteBuffer(azimuth_valid.data(), azimuth_valid.size());
  out.WriteBuffer(power.data(), power.size());
  const bool chirps = hasChirpDirections() && azimuth_chirp.size() == num_azimuths;
  out << static_cast<std::uint8_t>(chirps ? 1 : 0);
  if (chirps) out.WriteBuffer(azimuth_chirp.data(), azimuth_chirp.size());
}

void CObservationRadarScan::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) {
  if (version > 1) MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
  std::uint32_t label_bytes = 0;  // the layout of `in >> sensorLabel`, with a bound on the length
  in >> label_bytes;
  if (label_bytes > kMaxLabelBytes) THROW_EXCEPTION_FMT("corrupt radar scan: label of %u bytes", label_bytes);
  sensorLabel.resize(label_bytes);
  if (label_bytes > 0 && in.ReadBuffer(sensorLabel.data(), label_bytes) != label_bytes)
    throw mrpt::serialization::CExceptionEOF("radar scan label ends early");
  in >> timestamp >> sensorPose;
  in >> num_azimuths >> num_bins >> range_resolution_m >> range_offset_m;
  if (num_azimuths > kMaxAzimuths || num_bins > kMaxBins ||
      static_cast<std::uint64_t>(num_azimuths) * num_bins > kMaxCells)
    THROW_EXCEPTION_FMT("corrupt radar scan: implausible size %ux%u", num_azimuths, num_bins);
  azimuth_stamps_ns.resize(num_azimuths);
  azimuth_angles_rad.resize(num_azimuths);
  azimuth_valid.resize(num_azimuths);
  power.resize(static_cast<std::size_t>(num_azimuths) * num_bins);
  in.ReadBufferFixEndianness(azimuth_stamps_ns.data(), azimuth_stamps_ns.size());
  in.ReadBufferFixEndianness(azimuth_angles_rad.data(), azimuth_angles_rad.size());
  in.ReadBuffer(azimuth_valid.data(), azimuth_valid.size());
  in.ReadBuffer(power.data(), power.size());
  azimuth_chirp.assign(num_azimuths, 0);
  if (version >= 1) {
    std::uint8_t chirps = 0;
    in >> chirps;
    if (chirps > 1) THROW_EXCEPTION_FMT("corrupt radar scan: chirp flag %u", static_cast<unsigned>(chirps));
    if (chirps == 1 && in.ReadBuffer(azimuth_chirp.data(), azimuth_chirp.size()) != azimuth_chirp.size())
      throw mrpt::serialization::CExceptionEOF("radar scan chirp directions end early");
  }
}

}  // namespace radarslam
