#pragma once
// Per-scan benchmark outputs of `radarslam localize` (docs/localization.md, issue #14): the pose
// relative to the map keyframe it was matched to, its inverse covariance, and the Boreas
// localisation benchmark row (pyboreas eval/localization.md).
#include <radarslam/map/keyframe_map.h>
#include <radarslam/reloc/localizer.h>

#include <Eigen/Core>
#include <string>

namespace radarslam::cli {

/// The localised scan's pose in the frame of map keyframe r.keyframe, with its covariance.
struct KeyframeRelativePose {
  mrpt::math::TPose2D pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};
KeyframeRelativePose relativeToKeyframe(const KeyframeMap& map, const LocalizationResult& r);

/// Columns appended to a side-file row (names in kSideFileExtraHeader): keyframe id and stamp, the
/// pose relative to it, the upper triangle of the 3x3 inverse covariance (x, y, phi), the failed check.
extern const char* const kSideFileExtraHeader;
std::string sideFileExtra(const KeyframeMap& map, const LocalizationResult& r);

/// Boreas localisation row (localised scans only): test stamp us, keyframe stamp us, the upper 3x4
/// of T_keyframe_scan (row major, z = 0), the 6x6 inverse covariance (x, y, z, rx, ry, rz; row
/// major; no information, 0, in z, rx, ry). Ends with a newline.
std::string boreasRow(const KeyframeMap& map, const LocalizationResult& r);

}  // namespace radarslam::cli
