#pragma once
// Keyframe insertion shared by SLAM and by the ground-truth map builder (`radarslam map-synth`):
// the keyframe policy (every keyframe_distance_m or keyframe_angle_rad, as the RadarSLAM authors'
// config: 2 m / 0.2 rad) and appending a keyframe with its peak cloud and an odometry edge.
#include <array>
#include <cstdint>
#include <vector>

#include "radarslam/map/keyframe_map.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

class YamlParams;

struct KeyframeInsertionParams {
  double keyframe_distance_m = 2.0;  ///< valid [0, 10000]
  double keyframe_angle_rad = 0.2;   ///< valid [0, 6.2832]
  /// Diagonal information (x, y, phi) of the odometry edge to the previous keyframe.
  std::array<double, 3> odometry_information{100.0, 100.0, 1000.0};
};

/// Overrides from the keys keyframe_distance_m, keyframe_angle_rad of `yaml`.
void loadParams(const YamlParams& yaml, KeyframeInsertionParams& params);

/// True if `map` has no keyframe yet or `pose` is far enough (distance or angle) from the last one.
bool needsKeyframe(const KeyframeMap& map, const mrpt::math::TPose2D& pose,
                   const KeyframeInsertionParams& params);

/// Appends a keyframe (id = last id + 1, or 0) with the cloud's x, y, power and, if there is a
/// previous keyframe, an odometry edge from it with the relative pose. Returns the new id.
std::uint64_t addKeyframe(KeyframeMap& map, StampNs stamp, const mrpt::math::TPose2D& pose,
                          const std::vector<RadarPoint>& cloud, std::vector<float> descriptor = {},
                          const KeyframeInsertionParams& params = {});

}  // namespace radarslam
