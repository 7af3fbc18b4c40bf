// slam/loop_proximity.h: where M2DP finds no candidate, the keyframes the drift gate would let
// through are the candidates — an earlier pass within reach in the map, nearest first; never the
// recent ones, never a keyframe without a descriptor, never more than detector.max_candidates.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "loop_proximity.h"

namespace radarslam::slam_detail {
namespace {

/// Out along +x for `n` keyframes 2 m apart, then back along -x 3.7 m to the side (a U-turn):
/// keyframe n + i is on the way back at x = 2 (n - 1 - i).
void outAndBack(SlamState& s, int n) {
  double travelled = 0;
  for (int i = 0; i < 2 * n; ++i) {
    SlamKeyframe kf;
    kf.id = static_cast<std::uint64_t>(i);
    const bool back = i >= n;
    kf.pose = back ? TPose2D(2.0 * (2 * n - 1 - i), 3.7, M_PI) : TPose2D(2.0 * i, 0, 0);
    kf.travelled_m = travelled;
    travelled += 2.0;
    kf.descriptor = M2DPDescriptor::Constant(4, static_cast<float>(i));
    s.keyframes.push_back(kf);
  }
}

LoopClosingParams params(double max_translation_m) {
  LoopClosingParams p;
  p.verifier.max_translation_m = max_translation_m;
  p.detector.exclude_recent = 30;
  p.detector.exclude_recent_distance_m = 50;
  p.detector.max_candidates = 5;
  return p;
}

}  // namespace

TEST(LoopProximity, TheEarlierPassWithinTheDriftBoundNearestFirst) {
  SlamState s;
  outAndBack(s, 100);
  const std::uint64_t query = 150;  // on the way back at x = 98
  const M2DPDescriptor d = M2DPDescriptor::Constant(4, 150.0f);
  const auto c =
      proximityCandidates(s, query, std::span(&d, 1), params(2.0), [](std::uint64_t) { return 3.0; });
  // Within 2 + 3 m of (98, 3.7): the outbound keyframes at x = 96, 98, 100 (3.7 and 4.2 m off).
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].keyframe, 49u);                      // x = 98: 3.7 m
  EXPECT_EQ(c[1].keyframe, 48u);                      // x = 96: 4.2 m (ties keep the keyframe order)
  EXPECT_EQ(c[2].keyframe, 50u);                      // x = 100: 4.2 m
  EXPECT_FLOAT_EQ(c[0].distance, 2.0f * (150 - 49));  // |(150 - 49) * ones(4)|
  // A wider bound: more of the earlier pass, still at most max_candidates, nearest first.
  const auto wide =
      proximityCandidates(s, query, std::span(&d, 1), params(2.0), [](std::uint64_t) { return 30.0; });
  ASSERT_EQ(wide.size(), 5u);
  EXPECT_EQ(wide[0].keyframe, 49u);
  for (std::size_t i = 1; i < wide.size(); ++i) {
    const auto& a = s.keyframes[wide[i - 1].keyframe].pose;
    const auto& b = s.keyframes[wide[i].keyframe].pose;
    EXPECT_LE(std::hypot(a.x - 98, a.y - 3.7), std::hypot(b.x - 98, b.y - 3.7));
  }
}

TEST(LoopProximity, NeverTheRecentKeyframesNorOneWithoutDescriptor) {
  SlamState s;
  outAndBack(s, 100);
  const M2DPDescriptor d = M2DPDescriptor::Constant(4, 0.0f);
  const auto all = [](std::uint64_t) { return 1e6; };  // the whole map is within reach
  // Just after the U-turn (query 110, x = 178): the outbound keyframes near it were driven < 50 m
  // ago or are among the last 30.
  for (const auto& c : proximityCandidates(s, 110, std::span(&d, 1), params(2.0), all)) {
    EXPECT_LT(c.keyframe + 30, 110u);
    EXPECT_GE(s.keyframes[110].travelled_m - s.keyframes[c.keyframe].travelled_m, 50.0);
  }
  s.keyframes[49].descriptor.resize(0);
  const M2DPDescriptor q = M2DPDescriptor::Constant(4, 150.0f);
  const auto c =
      proximityCandidates(s, 150, std::span(&q, 1), params(2.0), [](std::uint64_t) { return 3.0; });
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].keyframe, 48u);
  EXPECT_EQ(c[1].keyframe, 50u);
  // A descriptor of another length compares with nothing: the candidates stay, at infinity.
  const M2DPDescriptor other = M2DPDescriptor::Constant(8, 0.0f);
  const auto far =
      proximityCandidates(s, 150, std::span(&other, 1), params(2.0), [](std::uint64_t) { return 3.0; });
  ASSERT_EQ(far.size(), 2u);
  EXPECT_EQ(far[0].distance, std::numeric_limits<float>::infinity());
}

TEST(LoopProximity, NothingWhereNoEarlierPassIsWithinReach) {
  SlamState s;
  outAndBack(s, 100);
  const M2DPDescriptor d = M2DPDescriptor::Constant(4, 0.0f);
  EXPECT_TRUE(
      proximityCandidates(s, 150, std::span(&d, 1), params(0.1), [](std::uint64_t) { return 1.0; }).empty());
  EXPECT_TRUE(
      proximityCandidates(s, 20, std::span(&d, 1), params(2.0), [](std::uint64_t) { return 1e6; }).empty());
}

}  // namespace radarslam::slam_detail
