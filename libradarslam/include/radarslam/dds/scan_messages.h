#pragma once
// CObservationRadarScan <-> radarslam/RadarScan message (all fields, exactly; sensorPose is not
// carried: a live driver publishes the radar frame, the localiser applies its own extrinsics).
#include <string>

#include "radarslam/dds/messages.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::dds {

/// header.stamp = the scan's reference time; header.frame_id = `frame_id`.
RadarScanMsg scanMessage(const CObservationRadarScan& scan, const std::string& frame_id = "radar");

/// Throws InputError("RadarScan message", problem) if the sizes do not match the geometry or the
/// result fails checkScanPlausible() (obs/scan_checks.h). sensorLabel = header.frame_id.
CObservationRadarScan::Ptr scanFromMessage(const RadarScanMsg& msg);

}  // namespace radarslam::dds
