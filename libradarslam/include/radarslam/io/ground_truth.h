#pragma once
// Ground-truth parsers. Each converts a dataset's own pose file to radarslam's one convention:
// the radar's absolute SE(2) pose (x, y, yaw) in a fixed world frame, with the sensor's angle
// convention (x = azimuth 0, y = azimuth 90 deg), as a Trajectory with strictly increasing stamps.
// Every problem is an InputError naming the file (and line where it applies).
#include <mrpt/poses/CPose3D.h>
#include <filesystem>
#include <vector>

#include "radarslam/core/trajectory.h"

namespace radarslam {

/// One row of Oxford's gt/radar_odometry.csv: the pose of the later scan ("source") expressed in
/// the earlier scan ("destination") frame. Timestamps in ns.
struct OxfordOdometryRow {
  StampNs source = 0, destination = 0;              ///< mid-sweep times
  StampNs source_radar = 0, destination_radar = 0;  ///< scan file names (first azimuth)
  mrpt::math::TPose2D motion;                       ///< x, y, yaw of T_destination_source
  std::size_t line = 0;                             ///< 1-based line in the CSV (0 = unknown)
};

/// Parses gt/radar_odometry.csv (header checked, 10 fields per row).
std::vector<OxfordOdometryRow> readOxfordOdometryRows(const std::filesystem::path& csv);

/// Chains the relative rows into absolute poses: identity at the first row's destination time,
/// then T_abs(source) = T_abs(destination) * T_rel at each row's source time. A row whose
/// destination time differs from the previous row's source time is a "ground-truth gap" error
/// naming `csv` and the line.
Trajectory chainOxfordOdometry(const std::vector<OxfordOdometryRow>& rows, const std::filesystem::path& csv);

/// readOxfordOdometryRows + chainOxfordOdometry.
Trajectory readOxfordGroundTruth(const std::filesystem::path& csv);

/// Projects a 3D sensor pose in a world frame to SE(2) in the sensor's angle convention. When
/// the sensor's z axis points down in the world (e.g. Boreas, roll ~ pi), the world is first
/// flipped (x, -y, -z) so that the SE(2) yaw increases in the same sense as the azimuth angle.
mrpt::math::TPose2D projectSensorPoseToSE2(const mrpt::poses::CPose3D& world_sensor);

/// Boreas applanix/radar_poses.csv: absolute radar poses (pyboreas' passive roll/pitch/yaw
/// convention, C = roll(r) * pitch(p) * yaw(y)), timestamps in us or ns by digit count.
Trajectory readBoreasGroundTruth(const std::filesystem::path& csv);

/// The fixed transform from MulRan's vehicle base to the radar (ORORA mulran_generate_gt.cpp):
/// yaw +0.9 deg, translation (1.50, -0.04, 1.97) m.
mrpt::poses::CPose3D mulranBaseToRadar();

/// MulRan global_pose.csv (no header; t_ns, then a row-major 3x4 [R|t] base pose): radar poses
/// (base pose * base_to_radar), expressed relative to the first one and projected to SE(2).
Trajectory readMulRanGroundTruth(const std::filesystem::path& csv,
                                 const mrpt::poses::CPose3D& base_to_radar = mulranBaseToRadar());

}  // namespace radarslam
