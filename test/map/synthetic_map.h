#pragma once
// A small synthetic KeyframeMap for the map tests: landmarks on a circle of radius 20 m around
// the origin (one per degree), keyframes inside it that observe every landmark, odometry edges
// between consecutive keyframes and one loop edge.
#include <cmath>

#include "radarslam/map/keyframe_map.h"

namespace radarslam::test {

constexpr double kLandmarkRadius = 20.0;

inline KeyframeMap syntheticMap(int num_keyframes = 8, int num_landmarks = 360) {
  KeyframeMap map;
  map.meta.sensor = {400, 3768, 0.0438, 0.1};
  map.meta.parameters_yaml =
      "frontend:\n  keyframe_distance_m: 2.0\npeak_cloud:\n  min_peak_prominence: 20\n";
  map.meta.created_ns = 1'700'000'000'123'456'789;
  map.meta.source_dataset = "/data/some dataset: seq 01";
  map.meta.software_version = "0.1.0-test";
  for (int l = 0; l < num_landmarks; ++l) {
    const double a = 2 * M_PI * l / num_landmarks;
    MapPoint p;
    p.id = 1000 + l;
    p.x = kLandmarkRadius * std::cos(a);
    p.y = kLandmarkRadius * std::sin(a);
    map.points.push_back(p);
  }
  for (int k = 0; k < num_keyframes; ++k) {
    Keyframe kf;
    kf.id = 10 + k;
    kf.stamp_ns = 1'500'000'000'000'000'000 + k * 250'000'000LL;
    const double t = 2 * M_PI * k / num_keyframes;
    kf.pose = {3.0 * std::cos(t), 3.0 * std::sin(t), t + 0.3};
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (auto& p : map.points) {
      const double dx = p.x - kf.pose.x, dy = p.y - kf.pose.y;
      kf.points.push_back({static_cast<float>(c * dx + s * dy), static_cast<float>(-s * dx + c * dy),
                           static_cast<float>(60 + (p.id * 7 + k) % 190)});
      p.observed_by.push_back(kf.id);
    }
    if (k % 2 == 0)
      for (int d = 0; d < 192; ++d) kf.descriptor.push_back(static_cast<float>(std::sin(0.1 * d + k)));
    map.keyframes.push_back(std::move(kf));
  }
  for (int k = 0; k + 1 < num_keyframes; ++k) {
    PoseGraphEdge e;
    e.from = 10 + k;
    e.to = 11 + k;
    e.relative = {0.5 + 0.01 * k, -0.2, 0.78};
    e.information = {100, 1, 0, 1, 100, 0, 0, 0, 400 + double(k)};
    map.edges.push_back(e);
  }
  PoseGraphEdge loop;
  loop.from = 10 + num_keyframes - 1;
  loop.to = 10;
  loop.relative = {1.25, 0.5, -0.1};
  loop.information = {50, 0, 0, 0, 50, 0, 0, 0, 200};
  loop.kind = EdgeKind::Loop;
  map.edges.push_back(loop);
  return map;
}

}  // namespace radarslam::test
