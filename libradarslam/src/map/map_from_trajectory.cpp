#include "radarslam/map/map_from_trajectory.h"

#include <mrpt/poses/CPose2D.h>

#include <cmath>

#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, KeyframeInsertionParams& params) {
  yaml.get("keyframe_distance_m", params.keyframe_distance_m, Range::closed(0, 10000.0));
  yaml.get("keyframe_angle_rad", params.keyframe_angle_rad, Range::closed(0, 6.2832));
}

bool needsKeyframe(const KeyframeMap& map, const mrpt::math::TPose2D& pose,
                   const KeyframeInsertionParams& params) {
  if (map.keyframes.empty()) return true;
  const auto& last = map.keyframes.back().pose;
  const double dphi = std::abs(std::remainder(pose.phi - last.phi, 2 * M_PI));
  return std::hypot(pose.x - last.x, pose.y - last.y) >= params.keyframe_distance_m ||
         dphi >= params.keyframe_angle_rad;
}

std::uint64_t addKeyframe(KeyframeMap& map, StampNs stamp, const mrpt::math::TPose2D& pose,
                          const std::vector<RadarPoint>& cloud, std::vector<float> descriptor,
                          const KeyframeInsertionParams& params) {
  Keyframe kf;
  kf.id = map.keyframes.empty() ? 0 : map.keyframes.back().id + 1;
  kf.stamp_ns = stamp;
  kf.pose = pose;
  kf.points.reserve(cloud.size());
  for (const auto& p : cloud) kf.points.push_back({p.x, p.y, p.power});
  kf.descriptor = std::move(descriptor);
  if (!map.keyframes.empty()) {
    const auto& prev = map.keyframes.back();
    PoseGraphEdge e;
    e.from = prev.id;
    e.to = kf.id;
    e.relative = (mrpt::poses::CPose2D(pose) - mrpt::poses::CPose2D(prev.pose)).asTPose();
    e.information = {params.odometry_information[0], 0, 0, 0, params.odometry_information[1], 0, 0, 0,
                     params.odometry_information[2]};
    e.kind = EdgeKind::Odometry;
    map.edges.push_back(e);
  }
  map.keyframes.push_back(std::move(kf));
  return map.keyframes.back().id;
}

}  // namespace radarslam
