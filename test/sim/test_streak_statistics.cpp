// sim/streak_statistics.h: narrow azimuths lit along their whole range are counted by how far they
// stand above their neighbours; a wide lit sector and single bright targets are not streaks.
#include <gtest/gtest.h>

#include <algorithm>

#include "radarslam/core/errors.h"
#include "radarslam/sim/streak_statistics.h"

using namespace radarslam;
using namespace radarslam::sim;

namespace {
CObservationRadarScan flatScan(std::size_t azimuths, std::uint8_t floor_code) {
  CObservationRadarScan s;
  s.resize(azimuths, 4000);
  s.range_resolution_m = 0.05;  // 200 m
  for (std::size_t a = 0; a < azimuths; ++a)
    for (std::size_t b = 0; b < 4000; ++b) s.row(a)[b] = static_cast<std::uint8_t>(floor_code + (a + b) % 3);
  return s;
}
void light(CObservationRadarScan& s, std::size_t a, int codes) {
  for (auto& v : s.row(a)) v = static_cast<std::uint8_t>(std::min(255, v + codes));
}
}  // namespace

TEST(StreakStatistics, CountsNarrowStreaksByTheirStrength) {
  CObservationRadarScan s = flatScan(100, 6);
  light(s, 10, 20);  // >= 6, 10, 15
  light(s, 40, 12);  // >= 6, 10
  light(s, 70, 7);   // >= 6 only
  light(s, 71, 3);   // too weak
  const StreakFractions f = computeStreakFractions(s);
  EXPECT_EQ(f.azimuths, 100u);
  EXPECT_DOUBLE_EQ(f.fraction[0], 0.03);
  EXPECT_DOUBLE_EQ(f.fraction[1], 0.02);
  EXPECT_DOUBLE_EQ(f.fraction[2], 0.01);
}

TEST(StreakStatistics, AWideLitSectorAndPointTargetsAreNotStreaks) {
  CObservationRadarScan s = flatScan(100, 6);
  for (std::size_t a = 30; a < 50; ++a) light(s, a, 30);  // a sector 20 azimuths wide
  for (std::size_t a = 0; a < 100; a += 7)                // bright targets, a few bins each
    for (std::size_t b = 1000; b < 1010; ++b) s.row(a)[b] = 200;
  const StreakFractions f = computeStreakFractions(s);
  for (double x : f.fraction) EXPECT_EQ(x, 0.0);
}

TEST(StreakStatistics, OnlyTheBandCountsAndTheAverageWeighsAzimuths) {
  CObservationRadarScan s = flatScan(100, 6);
  for (std::size_t b = 0; b < 300; ++b) s.row(5)[b] = 250;  // lit only within 15 m: outside 20-160 m
  EXPECT_EQ(computeStreakFractions(s).fraction[0], 0.0);
  light(s, 5, 20);
  const StreakFractions one = computeStreakFractions(s);
  const StreakFractions none = computeStreakFractions(flatScan(300, 6));
  const StreakFractions mean = averageStreaks({one, none});
  EXPECT_EQ(mean.azimuths, 400u);
  EXPECT_DOUBLE_EQ(mean.fraction[2], 1.0 / 400);
}

TEST(StreakStatistics, RejectsAnInvalidBandOrNeighbourhood) {
  const CObservationRadarScan s = flatScan(20, 6);
  EXPECT_THROW(computeStreakFractions(s, {.min_m = 50, .max_m = 40}), InputError);
  EXPECT_THROW(computeStreakFractions(s, {.neighbour_min = 0}), InputError);
  EXPECT_THROW(computeStreakFractions(s, {.neighbour_min = 3, .neighbour_max = 10}), InputError);
}
