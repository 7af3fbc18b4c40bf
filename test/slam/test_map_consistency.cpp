// slam/map_consistency.h: a street driven out and back is one street in the map when the map's
// relative poses of the revisit pairs equal the truth's; a map whose return leg is shifted fails
// exactly those pairs; consecutive pairs are not revisits.
#include <gtest/gtest.h>

#include "radarslam/slam/map_consistency.h"

namespace radarslam {
namespace {

using mrpt::math::TPose2D;

/// Out along y = 0 for 200 m and back 0.6 m to the side (another lane), a keyframe every 2 m.
void outAndBack(KeyframeMap& map, Trajectory& gt, double return_shift_m) {
  std::uint64_t id = 0;
  auto add = [&](double x, double y, double phi, double shift) {
    const StampNs t = static_cast<StampNs>(id + 1) * 250'000'000;
    gt.push_back({t, TPose2D(x, y, phi)});
    Keyframe kf;
    kf.id = id++;
    kf.stamp_ns = t;
    kf.pose = TPose2D(x + shift, y, phi);
    map.keyframes.push_back(kf);
  };
  for (int i = 0; i <= 100; ++i) add(2.0 * i, 0, 0, 0);
  for (int i = 100; i >= 0; --i) add(2.0 * i, 0.6, M_PI, return_shift_m);
}

TEST(MapConsistency, AStreetDrivenTwiceAndMappedRightIsConsistent) {
  KeyframeMap map;
  Trajectory gt;
  outAndBack(map, gt, 0.0);
  const MapConsistency mc = evaluateMapConsistency(map, gt);
  EXPECT_GT(mc.revisits.pairs, 500u);
  EXPECT_EQ(mc.revisits.consistent, mc.revisits.pairs);
  EXPECT_DOUBLE_EQ(mc.revisits.fraction, 1.0);
}

TEST(MapConsistency, AShiftedReturnLegFailsItsRevisitPairsOnly) {
  KeyframeMap map;
  Trajectory gt;
  outAndBack(map, gt, 0.5);  // the return leg is 0.5 m off along the street
  const MapConsistency mc = evaluateMapConsistency(map, gt);
  // Pairs within one leg are consistent; pairs across the legs (the revisits, but also the
  // turn-around's near-consecutive ones) are off by 0.5 m.
  EXPECT_LT(mc.revisits.fraction, 0.05);
  EXPECT_NEAR(mc.revisits.median_error_m, 0.5, 1e-6);
  EXPECT_GT(mc.all.fraction, 0.5);
}

TEST(MapConsistency, NoRevisitNoRevisitPairs) {
  KeyframeMap map;
  Trajectory gt;
  for (int i = 0; i < 100; ++i) {
    Keyframe kf;
    kf.id = static_cast<std::uint64_t>(i);
    kf.stamp_ns = (i + 1) * 250'000'000LL;
    kf.pose = TPose2D(2.0 * i, 0, 0);
    map.keyframes.push_back(kf);
    gt.push_back({kf.stamp_ns, kf.pose});
  }
  const MapConsistency mc = evaluateMapConsistency(map, gt);
  EXPECT_EQ(mc.revisits.pairs, 0u);
  EXPECT_GT(mc.all.pairs, 0u);
  EXPECT_DOUBLE_EQ(mc.revisits.fraction, 1.0);
}

}  // namespace
}  // namespace radarslam
