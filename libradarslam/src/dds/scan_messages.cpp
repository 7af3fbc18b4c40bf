#include "radarslam/dds/scan_messages.h"

#include "radarslam/core/errors.h"
#include "radarslam/obs/scan_checks.h"

namespace radarslam::dds {

RadarScanMsg scanMessage(const CObservationRadarScan& scan, const std::string& frame_id) {
  RadarScanMsg m;
  m.header.stamp = toTimeMsg(scan.refStampNs());
  m.header.frame_id = frame_id;
  m.num_azimuths = scan.num_azimuths;
  m.num_bins = scan.num_bins;
  m.range_resolution = scan.range_resolution_m;
  m.range_offset = scan.range_offset_m;
  m.azimuth_stamps_ns.assign(scan.azimuth_stamps_ns.begin(), scan.azimuth_stamps_ns.end());
  m.azimuth_angles = scan.azimuth_angles_rad;
  m.azimuth_valid = scan.azimuth_valid;
  m.power = scan.power;
  return m;
}

CObservationRadarScan::Ptr scanFromMessage(const RadarScanMsg& msg) {
  const std::size_t a = msg.num_azimuths;
  if (a == 0 || msg.num_bins == 0 || msg.azimuth_stamps_ns.size() != a || msg.azimuth_angles.size() != a ||
      msg.azimuth_valid.size() != a || msg.power.size() != a * msg.num_bins)
    throw InputError("RadarScan message", "array sizes do not match " + std::to_string(msg.num_azimuths) +
                                              " azimuths x " + std::to_string(msg.num_bins) + " bins");
  auto scan = CObservationRadarScan::Create();
  scan->num_azimuths = msg.num_azimuths;
  scan->num_bins = msg.num_bins;
  scan->range_resolution_m = msg.range_resolution;
  scan->range_offset_m = msg.range_offset;
  scan->power = msg.power;
  scan->azimuth_stamps_ns.assign(msg.azimuth_stamps_ns.begin(), msg.azimuth_stamps_ns.end());
  scan->azimuth_angles_rad = msg.azimuth_angles;
  scan->azimuth_valid = msg.azimuth_valid;
  scan->sensorLabel = msg.header.frame_id;
  scan->updateReferenceTime();
  if (const std::string problem = checkScanPlausible(*scan); !problem.empty())
    throw InputError("RadarScan message", problem);
  return scan;
}

}  // namespace radarslam::dds
