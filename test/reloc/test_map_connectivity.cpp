// The keyframe graph that tells two copies of a street apart (reloc/map_connectivity.h).
#include <gtest/gtest.h>

#include "radarslam/reloc/map_connectivity.h"

namespace radarslam {
namespace {

/// Keyframes (ids 10, 11, ...) every 10 m along x.
KeyframeMap chain(std::size_t n) {
  KeyframeMap map;
  for (std::size_t k = 0; k < n; ++k) {
    Keyframe kf;
    kf.id = 10 + k;
    kf.pose = {10.0 * static_cast<double>(k), 0, 0};
    map.keyframes.push_back(kf);
  }
  return map;
}

PoseGraphEdge edge(std::uint64_t from, std::uint64_t to, double length, EdgeKind kind = EdgeKind::Odometry) {
  PoseGraphEdge e;
  e.from = from;
  e.to = to;
  e.relative = {length, 0, 0};
  e.kind = kind;
  return e;
}

TEST(MapConnectivity, PathDistanceFollowsOdometryAndLoopEdges) {
  KeyframeMap map = chain(5);
  for (std::uint64_t k = 10; k < 14; ++k) map.edges.push_back(edge(k, k + 1, 10));
  const MapConnectivity g(map);
  EXPECT_EQ(g.within(0, 15), (std::vector<char>{1, 1, 0, 0, 0}));
  EXPECT_EQ(g.within(2, 10), (std::vector<char>{0, 1, 1, 1, 0}));
  // A loop edge (a merged revisit) brings the far end close.
  map.edges.push_back(edge(14, 10, 1, EdgeKind::Loop));
  EXPECT_EQ(MapConnectivity(map).within(0, 15), (std::vector<char>{1, 1, 0, 1, 1}));
}

TEST(MapConnectivity, ShortestPathTakesTheMergedRevisit) {
  KeyframeMap map = chain(6);
  for (std::uint64_t k = 10; k < 15; ++k) map.edges.push_back(edge(k, k + 1, 10));
  const MapConnectivity along(map);
  EXPECT_EQ(along.path(1, 4), (std::vector<std::size_t>{1, 2, 3, 4}));
  EXPECT_EQ(along.path(4, 1), (std::vector<std::size_t>{4, 3, 2, 1}));
  EXPECT_EQ(along.path(2, 2), (std::vector<std::size_t>{2}));
  // The drive came back to keyframe 0 at keyframe 5 (a loop edge, 1 m): 0 -> 5 -> 4 (11 m), not
  // 0 -> 1 -> ... -> 4 (40 m).
  map.edges.push_back(edge(15, 10, 1, EdgeKind::Loop));
  EXPECT_EQ(MapConnectivity(map).path(0, 4), (std::vector<std::size_t>{0, 5, 4}));
  EXPECT_TRUE(MapConnectivity(map).path(0, 6).empty());  // out of range
}

TEST(MapConnectivity, UnconnectedCopyIsNeverWithinReach) {
  KeyframeMap map = chain(6);  // 0-2 one copy, 3-5 another, no edge between them
  map.edges = {edge(10, 11, 10), edge(11, 12, 10), edge(13, 14, 10), edge(14, 15, 10)};
  map.edges.push_back(edge(10, 99, 1));  // an edge to an unknown id is ignored
  EXPECT_EQ(MapConnectivity(map).within(1, 1e9), (std::vector<char>{1, 1, 1, 0, 0, 0}));
  EXPECT_TRUE(MapConnectivity(map).path(0, 4).empty());
}

TEST(MapConnectivity, MapWithoutEdgesIsOneChainAndBadStartMeansEverything) {
  const KeyframeMap map = chain(4);
  const MapConnectivity g(map);
  EXPECT_EQ(g.within(3, 20), (std::vector<char>{0, 1, 1, 1}));
  EXPECT_EQ(g.within(7, 0), (std::vector<char>{1, 1, 1, 1}));
}

}  // namespace
}  // namespace radarslam
