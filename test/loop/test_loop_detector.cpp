// Candidate retrieval: exclusion of recent keyframes, top-k under a threshold, both PCA signs,
// and revisits in the opposite direction found through M2DP's rotation invariance.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/loop/loop_detector.h"
#include "synthetic_world.h"

namespace radarslam {
namespace {

M2DPDescriptor unit(int dim, int hot, float eps = 0) {
  M2DPDescriptor d = M2DPDescriptor::Zero(dim);
  d(hot) = 1;
  d(0) += eps;
  return d;
}

TEST(LoopDetector, ExcludesRecentKeyframesByCountAndDistance) {
  LoopDetectorParams p;
  p.exclude_recent = 3;
  p.exclude_recent_distance_m = 10;
  p.max_descriptor_distance = 0.5f;
  LoopDetector db(p);
  // Keyframes 0..9, 5 m apart, all with the same descriptor.
  for (int i = 0; i < 10; ++i) db.add(unit(8, 1), 5.0 * i);
  const auto c = db.query(unit(8, 1), 50.0);
  // Last 3 (7, 8, 9) by count; 8 and 9 also by distance (< 10 m before 50 m).
  ASSERT_EQ(c.size(), p.max_candidates);
  for (const auto& k : c) EXPECT_LT(k.keyframe, 7u);
  // Larger distance window: keyframes driven less than 30 m before are excluded.
  p.exclude_recent_distance_m = 30;
  LoopDetector db2(p);
  for (int i = 0; i < 10; ++i) db2.add(unit(8, 1), 5.0 * i);
  for (const auto& k : db2.query(unit(8, 1), 50.0)) EXPECT_LE(k.keyframe, 4u);
}

TEST(LoopDetector, IsRecentByCountOrByDistance) {
  LoopDetectorParams p;
  p.exclude_recent = 3;
  p.exclude_recent_distance_m = 10;
  // Query keyframe 10 at 100 m.
  EXPECT_TRUE(isRecent(p, 7, 0.0, 10, 100.0));    // one of the last 3 keyframes
  EXPECT_FALSE(isRecent(p, 6, 0.0, 10, 100.0));   // 4 keyframes and 100 m before
  EXPECT_TRUE(isRecent(p, 2, 95.0, 10, 100.0));   // only 5 m driven since
  EXPECT_FALSE(isRecent(p, 2, 90.0, 10, 100.0));  // exactly the distance window
}

TEST(LoopDetector, ReturnsTopKUnderTheThresholdBestFirst) {
  LoopDetectorParams p;
  p.exclude_recent = 0;
  p.exclude_recent_distance_m = 0;
  p.max_candidates = 2;
  p.max_descriptor_distance = 0.3f;
  LoopDetector db(p);
  db.add(unit(8, 2, 0.2f), 0);   // 0.2 away
  db.add(unit(8, 3), 1);         // far
  db.add(unit(8, 2, 0.05f), 2);  // 0.05 away
  db.add(unit(8, 2, 0.1f), 3);   // 0.1 away
  db.add(M2DPDescriptor(), 4);   // invalid keyframe: stored, never returned
  EXPECT_EQ(db.size(), 5u);
  const auto c = db.query(unit(8, 2), 10);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].keyframe, 2u);
  EXPECT_EQ(c[1].keyframe, 3u);
  EXPECT_NEAR(c[0].distance, 0.05f, 1e-6);
  EXPECT_TRUE(db.query(unit(8, 5), 10).empty());
  EXPECT_THROW(db.add(unit(9, 1), 5), std::invalid_argument);
  // Several query descriptors (e.g. both PCA signs): each keyframe once, with its best distance.
  const std::vector<M2DPDescriptor> both{unit(8, 3, 0.01f), unit(8, 2)};
  const auto c2 = db.query(both, 10);
  ASSERT_EQ(c2.size(), 2u);
  EXPECT_EQ(c2[0].keyframe, 1u);
}

// A drive through a random world: keyframes every 5 m along a street, then the same street driven
// back in the opposite direction. Each return keyframe must retrieve a keyframe of the outbound
// drive within 5 m of it.
TEST(LoopDetector, FindsOppositeDirectionRevisits) {
  const auto world = looptest::randomWorld(21);
  LoopDetectorParams p;
  p.exclude_recent = 10;
  p.exclude_recent_distance_m = 60;
  LoopDetector db(p);
  const int n = 30;
  double travelled = 0;
  for (int i = 0; i < n; ++i, travelled += 5) {
    const auto cloud = looptest::observe(world, -75 + 5.0 * i, 3.0, 0.0, 100 + static_cast<unsigned>(i));
    db.add(computeM2DP(cloud), travelled);
  }
  // A detour elsewhere (these keyframes are the recent ones when the drive comes back).
  for (int i = 0; i < 15; ++i, travelled += 10)
    db.add(computeM2DP(looptest::observe(world, -70 + 10.0 * i, 140.0, 0.0, 300 + static_cast<unsigned>(i))),
           travelled);
  int found = 0, wrong = 0, queries = 0;
  for (int i = n - 1; i >= 0; i -= 3, travelled += 15) {
    const double x = -75 + 5.0 * i + 1.0;
    const auto cloud = looptest::observe(world, x, 0.0, M_PI + 0.05, 500 + static_cast<unsigned>(i));
    const std::vector<M2DPDescriptor> both{computeM2DP(cloud), computeM2DP(cloud, {}, true)};
    const auto c = db.query(both, travelled);
    ++queries;
    bool hit = false;
    for (const auto& k : c) {
      const double kx = -75 + 5.0 * static_cast<double>(k.keyframe);
      if (std::abs(kx - x) <= 6) hit = true;
    }
    found += hit;
    wrong += !c.empty() && !hit;
  }
  EXPECT_GE(found, queries - 1) << found << " of " << queries;
  EXPECT_LE(wrong, 1);
}

TEST(LoopDetector, ParamsFromYaml) {
  LoopDetectorParams p;
  loadParams(YamlParams::fromText("max_candidates: 5\nexclude_recent: 7\n"), p);
  EXPECT_EQ(p.max_candidates, 5u);
  EXPECT_EQ(p.exclude_recent, 7u);
  EXPECT_THROW(loadParams(YamlParams::fromText("max_candidates: 0\n"), p), InputError);
}

}  // namespace
}  // namespace radarslam
