// Motion compensation of stored keyframe clouds; see reloc/map_motion.h.
#include "radarslam/reloc/map_motion.h"

#include <mrpt/poses/CPose2D.h>

#include <cmath>

#include "radarslam/frontend/motion_compensation.h"

namespace radarslam {

KeyframeMap compensateMapMotion(const KeyframeMap& map, double sweep_period_s) {
  KeyframeMap out = map;
  const auto& kfs = map.keyframes;
  const StampNs max_gap = 2 * kNsPerSec;
  for (std::size_t k = 0; k < kfs.size(); ++k) {
    // Neighbours in time, within max_gap of this keyframe.
    const std::size_t a = (k > 0 && kfs[k].stamp_ns - kfs[k - 1].stamp_ns <= max_gap) ? k - 1 : k;
    const std::size_t b =
        (k + 1 < kfs.size() && kfs[k + 1].stamp_ns - kfs[k].stamp_ns <= max_gap) ? k + 1 : k;
    if (a == b || kfs[b].stamp_ns <= kfs[a].stamp_ns) continue;
    const mrpt::math::TPose2D delta =
        (mrpt::poses::CPose2D(kfs[b].pose) - mrpt::poses::CPose2D(kfs[a].pose)).asTPose();
    const BodyVelocity v = twistFromDelta(delta, toSeconds(kfs[b].stamp_ns - kfs[a].stamp_ns));
    for (auto& p : out.keyframes[k].points) {
      double bearing = std::atan2(static_cast<double>(p.y), static_cast<double>(p.x));
      if (bearing < 0) bearing += 2 * M_PI;
      const double dt = (bearing / (2 * M_PI) - 0.5) * sweep_period_s;
      double qx = 0, qy = 0;
      integrateTwist(v, dt).apply(p.x, p.y, qx, qy);
      p.x = static_cast<float>(qx);
      p.y = static_cast<float>(qy);
    }
  }
  return out;
}

}  // namespace radarslam
