#pragma once
// Motion compensation of a stored map's keyframe clouds, for maps whose clouds are the raw
// Algorithm-1 peaks of a moving sensor (today: `radarslam map-synth`, which stores
// extractPeakCloud() output as is). A sweep takes ~0.25 s, so at 13 m/s the returns of one scan
// are up to ~1.6 m out of place relative to the mid-sweep pose; a scan localised at standstill
// against such a map is biased along the road by up to that (measured in docs/localization.md).
// Each keyframe's body velocity is the ground-truth/SLAM motion between its neighbouring keyframes
// (map poses and stamps); each point's firing time follows from its bearing (azimuth 0 along +x is
// fired first, the reference time is mid-sweep, as CObservationRadarScan::refStampNs()).
#include "radarslam/map/keyframe_map.h"

namespace radarslam {

/// A copy of `map` with every keyframe cloud moved to its keyframe's reference time, assuming a
/// sweep of `sweep_period_s` seconds. Keyframes without a neighbour within 2 s are left as they are.
KeyframeMap compensateMapMotion(const KeyframeMap& map, double sweep_period_s);

}  // namespace radarslam
