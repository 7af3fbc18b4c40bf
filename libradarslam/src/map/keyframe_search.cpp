#include "radarslam/map/keyframe_search.h"

namespace radarslam {

namespace {
double distance2(const Keyframe& kf, double x, double y) {
  return (kf.pose.x - x) * (kf.pose.x - x) + (kf.pose.y - y) * (kf.pose.y - y);
}
}  // namespace

long nearestKeyframe(const KeyframeMap& map, double x, double y,
                     const std::function<bool(std::size_t)>& eligible) {
  long best = -1;
  double best_d2 = 0;
  for (std::size_t k = 0; k < map.keyframes.size(); ++k) {
    if (eligible && !eligible(k)) continue;
    const double d2 = distance2(map.keyframes[k], x, y);
    if (best < 0 || d2 < best_d2) best = static_cast<long>(k), best_d2 = d2;
  }
  return best;
}

long nearestKeyframe(const KeyframeMap& map, double x, double y) {
  return nearestKeyframe(map, x, y, nullptr);
}

long nearestKeyframe(const KeyframeMap& map, std::span<const std::size_t> indices, double x, double y) {
  long best = -1;
  double best_d2 = 0;
  for (const std::size_t k : indices) {
    const double d2 = distance2(map.keyframes[k], x, y);
    if (best < 0 || d2 < best_d2) best = static_cast<long>(k), best_d2 = d2;
  }
  return best;
}

}  // namespace radarslam
