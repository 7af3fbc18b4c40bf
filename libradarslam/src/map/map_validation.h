#pragma once
// Content checks of a decoded map (loadMap runs them after the checksums): a map whose files were
// rewritten with valid checksums must still not carry NaN poses, dangling ids or a zero
// resolution into localisation, exports or the map server. Bounds are in maps/README.md.
#include <string>

#include "radarslam/map/keyframe_map.h"

namespace radarslam::mapcodec {

/// |x|, |y| of any pose or point in the map frame [m].
constexpr double kMaxCoordinateM = 1e7;
/// |phi| of any pose [rad] (poses need not be wrapped, but 1e300 is not an angle).
constexpr double kMaxAngleRad = 1e6;
/// |x|, |y| of a keyframe point in the sensor frame [m] (radar range).
constexpr double kMaxSensorRangeM = 1e5;

/// Each throws InputError(file, "<what>: <problem>") on the first bad value.
void validateSensor(const MapSensorGeometry& sensor, const std::string& manifest_file);
void validateKeyframes(const KeyframeMap& map, const std::string& file);
/// Needs the keyframes (ids referenced by the points / edges).
void validatePoints(const KeyframeMap& map, const std::string& file);
void validateGraph(const KeyframeMap& map, const std::string& file);

}  // namespace radarslam::mapcodec
