// compensateMapMotion: raw clouds of a moving sensor are moved to the mid-sweep pose.
#include <gtest/gtest.h>

#include <cmath>

#include "radarslam/reloc/localizer.h"
#include "radarslam/reloc/map_motion.h"

namespace radarslam {
namespace {

TEST(RelocMapMotion, RawSweepOfAMovingSensorIsCompensated) {
  const double v = 10.0, period = 0.25;  // m/s along x, s per sweep
  KeyframeMap map;
  std::vector<std::pair<double, double>> truth;  // points of the middle keyframe at mid-sweep
  for (int k = 0; k < 3; ++k) {
    Keyframe kf;
    kf.id = static_cast<std::uint64_t>(k);
    kf.stamp_ns = k * 250'000'000LL;
    kf.pose = {v * 0.25 * k, 0.0, 0.0};
    for (int i = 0; i < 36; ++i) {
      const double a = (i + 0.5) * 2 * M_PI / 36, r = 20 + i;
      const double px = r * std::cos(a), py = r * std::sin(a);
      // Fired at dt from mid-sweep, when the sensor was at x = v dt: seen at p - (v dt, 0).
      const double dt = (a / (2 * M_PI) - 0.5) * period;
      kf.points.push_back({static_cast<float>(px - v * dt), static_cast<float>(py), 100.f});
      if (k == 1) truth.emplace_back(px, py);
    }
    map.keyframes.push_back(kf);
  }
  const KeyframeMap out = compensateMapMotion(map, period);
  double raw_max = 0, comp_max = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto& r = map.keyframes[1].points[i];
    const auto& c = out.keyframes[1].points[i];
    raw_max = std::max(raw_max, std::hypot(r.x - truth[i].first, r.y - truth[i].second));
    comp_max = std::max(comp_max, std::hypot(c.x - truth[i].first, c.y - truth[i].second));
  }
  EXPECT_GT(raw_max, 1.0);    // up to v * period / 2 = 1.25 m out of place
  EXPECT_LT(comp_max, 0.05);  // bearing of the raw point vs the true one differs slightly
  EXPECT_EQ(out.keyframes[1].pose.x, map.keyframes[1].pose.x);
  // Zero period: nothing moves.
  EXPECT_EQ(compensateMapMotion(map, 0.0).keyframes, map.keyframes);
}

TEST(RelocMapMotion, OnlyAMapOfRawCloudsIsCompensated) {
  KeyframeMap map;
  LocalizerParams params;
  params.map_sweep_period_s = 0.25;
  map.meta.clouds_motion_compensated = false;  // map-synth
  EXPECT_TRUE(compensatesMap(map, params));
  map.meta.clouds_motion_compensated = true;  // radarslam map: never compensated twice
  EXPECT_FALSE(compensatesMap(map, params));
  map.meta.clouds_motion_compensated = false;
  params.map_sweep_period_s = 0;
  EXPECT_FALSE(compensatesMap(map, params));
}

}  // namespace
}  // namespace radarslam
