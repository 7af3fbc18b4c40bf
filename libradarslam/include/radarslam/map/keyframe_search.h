#pragma once
// The map keyframe nearest to a position in the plane (the localiser's anchor, its coverage check
// and the map-relative error all ask this).
#include <cstddef>
#include <functional>
#include <span>

#include "radarslam/map/keyframe_map.h"

namespace radarslam {

/// Index of the keyframe nearest to (x, y) among `indices`, or among all keyframes of `map` for
/// the overload without; -1 when there is none. Ties: the first.
long nearestKeyframe(const KeyframeMap& map, double x, double y);
long nearestKeyframe(const KeyframeMap& map, std::span<const std::size_t> indices, double x, double y);
/// Among the keyframes `eligible(k)` accepts.
long nearestKeyframe(const KeyframeMap& map, double x, double y,
                     const std::function<bool(std::size_t)>& eligible);

}  // namespace radarslam
