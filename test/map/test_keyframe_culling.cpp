// Keyframe culling before saving (map/keyframe_culling.h): a street driven a second time adds no
// keyframes where the first pass covers it, the graph stays connected, composed odometry edges
// keep the relative pose and grow their covariance, loop edges and map points follow.
#include <gtest/gtest.h>

#include <mrpt/poses/CPose2D.h>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <set>

#include "radarslam/map/keyframe_culling.h"

namespace radarslam {
namespace {

using Pose = mrpt::math::TPose2D;

Pose between(const Pose& a, const Pose& b) {
  return (mrpt::poses::CPose2D(b) - mrpt::poses::CPose2D(a)).asTPose();
}

/// Pass 1 along y = 0 from x = 0 to 100 (2 m steps), a U-turn, pass 2 back along y = 1.4 (the
/// other lane), then a new road up x = -10.
KeyframeMap twoPassMap() {
  KeyframeMap m;
  std::vector<Pose> poses;
  for (int i = 0; i <= 50; ++i) poses.push_back({2.0 * i, 0, 0});
  for (int i = 50; i >= 0; --i) poses.push_back({2.0 * i, 1.4, M_PI});
  for (int i = 1; i <= 30; ++i) poses.push_back({-10, 1.4 + 2.0 * i, M_PI / 2});
  for (std::size_t k = 0; k < poses.size(); ++k) {
    Keyframe kf;
    kf.id = 1000 + k;  // ids are not indices
    kf.stamp_ns = static_cast<StampNs>(k) * 250'000'000;
    kf.pose = poses[k];
    kf.points = {{1.f, 2.f, 50.f}};
    m.keyframes.push_back(kf);
  }
  for (std::size_t k = 1; k < poses.size(); ++k) {
    PoseGraphEdge e;
    e.from = 1000 + k - 1, e.to = 1000 + k;
    e.relative = between(poses[k - 1], poses[k]);
    e.information = {100, 0, 0, 0, 100, 0, 0, 0, 1000};
    m.edges.push_back(e);
  }
  for (std::size_t k = 60; k < 101; k += 5) {  // loops of pass 2 to pass 1 (same x)
    PoseGraphEdge e;
    e.from = 1000 + (101 - k), e.to = 1000 + k;  // pass-1 keyframe at the same x
    e.relative = between(poses[101 - k], poses[k]);
    e.information = {25, 0, 0, 0, 25, 0, 0, 0, 3000};
    e.kind = EdgeKind::Loop;
    m.edges.push_back(e);
  }
  for (std::size_t k = 0; k < poses.size(); ++k) {
    MapPoint p;
    p.id = k;
    p.x = poses[k].x, p.y = poses[k].y + 5;
    p.observed_by = {1000 + k};
    if (k >= 51 && k <= 101) p.observed_by.push_back(1000 + (101 - k));  // also seen from pass 1
    m.points.push_back(p);
  }
  return m;
}

TEST(KeyframeCulling, SecondPassAddsNoKeyframesWhereTheFirstCoversTheStreet) {
  KeyframeMap m = twoPassMap();
  const std::size_t n = m.keyframes.size();
  const CullingReport r = cullRedundantKeyframes(m, {});
  EXPECT_EQ(r.keyframes_before, n);
  EXPECT_EQ(r.keyframes_after, m.keyframes.size());
  std::set<std::uint64_t> kept;
  for (const auto& kf : m.keyframes) kept.insert(kf.id);
  // Pass 1 and the new road stay whole; pass 2 keeps only its first keyframes (less than 50 m of
  // path after the pass-1 keyframes within 2.5 m of them: the U-turn), 12 of 51.
  for (std::uint64_t k = 0; k <= 50; ++k) EXPECT_TRUE(kept.count(1000 + k)) << k;
  for (std::uint64_t k = 102; k < n; ++k) EXPECT_TRUE(kept.count(1000 + k)) << k;
  std::size_t pass2 = 0;
  for (std::uint64_t k = 51; k <= 101; ++k) pass2 += kept.count(1000 + k);
  EXPECT_EQ(pass2, 12u);
  EXPECT_TRUE(kept.count(1000 + 51));
  EXPECT_FALSE(kept.count(1000 + 101));

  // Every edge joins kept keyframes, and the graph is connected.
  std::map<std::uint64_t, std::set<std::uint64_t>> adj;
  for (const auto& e : m.edges) {
    ASSERT_TRUE(kept.count(e.from) && kept.count(e.to)) << e.from << " -> " << e.to;
    adj[e.from].insert(e.to), adj[e.to].insert(e.from);
  }
  std::set<std::uint64_t> seen{1000};
  std::vector<std::uint64_t> todo{1000};
  while (!todo.empty()) {
    const auto k = todo.back();
    todo.pop_back();
    for (const auto j : adj[k])
      if (seen.insert(j).second) todo.push_back(j);
  }
  EXPECT_EQ(seen.size(), kept.size());

  // The odometry edge across the dropped run: the composed relative pose, a larger covariance.
  const PoseGraphEdge* across = nullptr;
  for (const auto& e : m.edges)
    if (e.kind == EdgeKind::Odometry && e.from == 1000 + 62) across = &e;
  ASSERT_NE(across, nullptr);
  EXPECT_EQ(across->to, 1000u + 102);
  const Pose expected = between({2.0 * (101 - 62), 1.4, M_PI}, {-10, 3.4, M_PI / 2});
  EXPECT_NEAR(across->relative.x, expected.x, 1e-9);
  EXPECT_NEAR(across->relative.y, expected.y, 1e-9);
  EXPECT_NEAR(across->relative.phi, expected.phi, 1e-9);
  // 40 composed steps: the heading variances add up (0.001 each); position grows faster (lever arm).
  Eigen::Matrix3d info;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) info(i, j) = across->information[static_cast<std::size_t>(3 * i + j)];
  const Eigen::Matrix3d cov = info.inverse();
  EXPECT_NEAR(cov(2, 2), 40 * 0.001, 1e-9);
  EXPECT_GT(cov(0, 0) + cov(1, 1), 40 * 2 * 0.01);

  // Loop edges of dropped keyframes moved to the covering pass-1 keyframe (same place: ~identity
  // but for the lane offset and the heading).
  std::size_t loops = 0;
  for (const auto& e : m.edges)
    if (e.kind == EdgeKind::Loop) {
      ++loops;
      EXPECT_LT(e.from, 1000u + 51);
    }
  EXPECT_GT(loops, 0u);

  // Map points: dropped observers removed, a point seen only from dropped keyframes gone.
  for (const auto& p : m.points) {
    ASSERT_FALSE(p.observed_by.empty());
    for (const auto id : p.observed_by) EXPECT_TRUE(kept.count(id)) << p.id;
  }
  EXPECT_EQ(r.points_after, m.points.size());
  EXPECT_EQ(r.points_before, n);  // no point was seen only from dropped keyframes here
}

TEST(KeyframeCulling, DisabledOrOnePassChangesNothing) {
  KeyframeMap m = twoPassMap();
  const KeyframeMap before = m;
  KeyframeCullingParams off;
  off.enabled = false;
  cullRedundantKeyframes(m, off);
  EXPECT_EQ(m, before);
  // One pass: nothing is covered by an earlier pass (consecutive keyframes are < 50 m of path apart).
  KeyframeMap one;
  for (std::size_t k = 0; k < 51; ++k) one.keyframes.push_back(before.keyframes[k]);
  const KeyframeMap one_before = one;
  cullRedundantKeyframes(one, {});
  EXPECT_EQ(one, one_before);
}

}  // namespace
}  // namespace radarslam
