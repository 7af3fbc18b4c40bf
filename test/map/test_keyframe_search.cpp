// nearestKeyframe: among all keyframes, a subset of indices, or those a predicate accepts.
#include <gtest/gtest.h>

#include <vector>

#include "radarslam/map/keyframe_search.h"

namespace radarslam {

TEST(KeyframeSearch, NearestAmongAllASubsetOrTheEligible) {
  KeyframeMap map;
  for (int k = 0; k < 10; ++k) {  // along y = 0, every 5 m
    Keyframe kf;
    kf.pose = {5.0 * k, 0.0, 0.0};
    map.keyframes.push_back(kf);
  }
  EXPECT_EQ(nearestKeyframe(map, 21.0, 3.0), 4);
  EXPECT_EQ(nearestKeyframe(map, -50.0, 0.0), 0);
  EXPECT_EQ(nearestKeyframe(map, 12.5, 0.0), 2);  // a tie: the first
  const std::vector<std::size_t> subset{7, 8, 9};
  EXPECT_EQ(nearestKeyframe(map, subset, 21.0, 3.0), 7);
  EXPECT_EQ(nearestKeyframe(map, 21.0, 3.0, [](std::size_t k) { return k % 2 == 1; }), 5);
  EXPECT_EQ(nearestKeyframe(map, std::vector<std::size_t>{}, 0.0, 0.0), -1);
  EXPECT_EQ(nearestKeyframe(KeyframeMap{}, 0.0, 0.0), -1);
}

}  // namespace radarslam
