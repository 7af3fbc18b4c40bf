#pragma once
// Trajectory files: TUM (radarslam's output format for every estimated trajectory) and KITTI pose
// files, read into / written from radarslam's SE(2) Trajectory (core/trajectory.h).
//
// TUM:   one pose per line, `t x y z qx qy qz qw`, t in seconds (decimal, parsed exactly to the
//        nanosecond; integer stamps are read by digit count: 10 digits s, 13 ms, 16 us, 19 ns).
//        '#' starts a comment line. Written with 9 decimals (ns), z = 0 and a yaw quaternion.
// KITTI: one pose per line, 12 numbers = the row-major 3x4 matrix [R | t] (the pose of the frame in
//        the world). No stamps: they come from a companion file (one stamp per line, same syntax as
//        the TUM stamp or KITTI's `times.txt` "%e" seconds), or else the line index is the stamp in
//        seconds (0, 1, 2, ... s). A 13-column variant with the stamp first (pyboreas' benchmark
//        format) is read too.
// SE(2) projection: x, y and the yaw of the rotation about z (the x-y plane is the ground plane,
// z up or down). Poses tilted by more than 30 degrees (e.g. KITTI's camera frame with y down, z
// forward) are accepted with a warning: such a file needs converting before a planar evaluation.
//
// Every problem is an InputError whose where() is "<file>:<line>": malformed lines, non-finite
// numbers, non-unit quaternions, non-rotation matrices, stamps that do not strictly increase.
// Writers are atomic (core/atomic_file.h).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "radarslam/core/trajectory.h"

namespace radarslam {

enum class TrajectoryFormat { Auto, Tum, Kitti };

/// "tum", "kitti" or "auto" (case-insensitive); throws InputError(where, ...) otherwise.
TrajectoryFormat parseTrajectoryFormat(const std::string& name, const std::string& where);
std::string toString(TrajectoryFormat format);

/// The format of a trajectory file judged from its first data line: 8 columns TUM, 12 or 13 KITTI.
TrajectoryFormat detectTrajectoryFormat(const std::filesystem::path& file);

Trajectory readTumTrajectory(const std::filesystem::path& file);

/// KITTI poses. `stamps`: one stamp per pose (from a companion file), or empty to use the companion
/// `<stem>.times.txt` next to the file if it exists, else the line index in seconds.
Trajectory readKittiTrajectory(const std::filesystem::path& file, const std::vector<StampNs>& stamps = {});

/// Stamps, one per non-empty line (decimal or "%e" seconds, or an integer read by digit count).
std::vector<StampNs> readStampFile(const std::filesystem::path& file);

/// `dir/poses.txt` -> `dir/poses.times.txt`: where writeKittiTrajectory puts the stamps.
std::filesystem::path kittiStampsCompanion(const std::filesystem::path& kitti_file);

struct TrajectoryReadOptions {
  TrajectoryFormat format = TrajectoryFormat::Auto;
  std::optional<std::filesystem::path> stamps_file;  ///< KITTI only
};

/// Reads a TUM or KITTI file (format detected unless given).
Trajectory readTrajectoryFile(const std::filesystem::path& file, const TrajectoryReadOptions& options = {});

void writeTumTrajectory(const std::filesystem::path& file, const Trajectory& trajectory);
/// Writes the 3x4 poses and, next to them, the stamps (kittiStampsCompanion) so nothing is lost.
void writeKittiTrajectory(const std::filesystem::path& file, const Trajectory& trajectory);

/// "1547120788.016733000": exact seconds with 9 decimals, as the writers print stamps.
std::string formatStampSeconds(StampNs t);

/// Parses one stamp as the readers do (see above). False if `text` is not a stamp.
bool parseStampText(const std::string& text, StampNs& out);

}  // namespace radarslam
