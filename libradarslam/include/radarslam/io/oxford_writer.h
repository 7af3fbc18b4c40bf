#pragma once
// Writes a radar sequence in the Oxford Radar RobotCar layout (see shared FORMATS.md section 1),
// so that the same reader serves real and simulated data:
//   radar/<t_us>.png        rows = azimuths, cols 0-7 int64 LE us stamp, 8-9 uint16 LE encoder
//                           count (angle = count / encoder_size * 2 pi), 10 valid (255), then bins;
//                           a scan with chirp directions (alternating chirp, RAS6-like) has the
//                           chirp flag in byte 10 instead (255 up, 0 down), as Boreas-RT;
//                           the file name is the first azimuth's stamp
//   radar.timestamps        "<t_us> 1" per scan
//   gt/radar_odometry.csv   Oxford header; one row per consecutive pair: source = later scan,
//                           x,y,yaw = pose of the later scan in the earlier one, source/destination
//                           timestamps = mid-sweep times, *_radar_timestamp = file names
//   gt/poses.tum            absolute radar poses at mid-sweep times, "t x y z qx qy qz qw" (t in s)
//   radar.geometry          only when the range geometry is not Oxford's (0.0432 m/bin, bin
//                           centres): "range_resolution_m <m>" and "range_offset_m <m>" lines,
//                           because the Oxford PNG does not carry them (the Oxford reader reads it);
//                           plus "chirp_flag 1" when byte 10 is the chirp flag (then written even
//                           for Oxford's range geometry)
// Every file is written atomically; the index and ground truth files are written last (finish()).
#include <cstdint>
#include <filesystem>
#include <vector>

#include "radarslam/core/trajectory.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

/// The Oxford PNG bytes of a scan (PNG compression level 0-9; 1 is fast). Stamps are written in
/// whole microseconds; angles as encoder counts of `encoder_size`.
std::vector<unsigned char> encodeOxfordPng(const CObservationRadarScan& scan, int png_compression = 1,
                                           int encoder_size = 5600);

class OxfordWriter {
 public:
  /// Creates root/radar and root/gt.
  explicit OxfordWriter(std::filesystem::path root, int png_compression = 1, int encoder_size = 5600);

  /// Writes radar/<first azimuth us>.png and remembers the scan's stamps. `truth` is the radar's
  /// absolute pose at the scan's reference (mid-sweep) time.
  void writeScan(const CObservationRadarScan& scan, const mrpt::math::TPose2D& truth);

  /// Writes radar.geometry (if not Oxford's), radar.timestamps, then gt/radar_odometry.csv and
  /// gt/poses.tum.
  void finish();

  std::size_t scansWritten() const { return names_us_.size(); }
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
  int compression_, encoder_size_;
  double resolution_m_ = 0, offset_m_ = 0;  // of the first scan (all scans must agree)
  bool chirp_flag_ = false;                 // byte 10 holds the chirp flag (first scan decides)
  std::vector<std::int64_t> names_us_;      // first-azimuth stamps
  Trajectory truth_;                        // at mid-sweep times (ns)
};

}  // namespace radarslam
