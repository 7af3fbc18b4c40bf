// RadarSlam::extend refuses a base map it cannot continue, before any work starts.
#include <gtest/gtest.h>

#include <stdexcept>

#include "radarslam/slam/radar_slam.h"

namespace radarslam {

TEST(RadarSlamExtend, RefusesAMapWithoutKeyframesOrOfRawClouds) {
  KeyframeMap map;
  {
    RadarSlam slam(SlamParams{});
    EXPECT_THROW(slam.extend(map), std::invalid_argument);
  }
  Keyframe kf;
  kf.points.push_back({});
  map.keyframes.push_back(kf);
  map.meta.clouds_motion_compensated = false;  // map-synth: raw sweeps
  {
    RadarSlam slam(SlamParams{});
    EXPECT_THROW(slam.extend(map), std::invalid_argument);
  }
  map.meta.clouds_motion_compensated = true;
  RadarSlam slam(SlamParams{});
  EXPECT_NO_THROW(slam.extend(map));
}

}  // namespace radarslam
