// slam/loop_evaluation.h: an accepted loop is false when its relative pose is off the truth by more
// than 2 m or 3 degrees; a partial loop (along one line) only across its line and in heading, and it
// counts in neither the recall nor the error figures of full loops. Refused candidates are judged the
// same way and counted by why they were refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "radarslam/slam/loop_evaluation.h"

namespace radarslam {
namespace {

using mrpt::math::TPose2D;

/// A street driven along y = 0 and back along y = 5 (heading pi), a keyframe every 4 m: keyframe
/// i and 2n - 1 - i are at the same x.
void outAndBack(KeyframeMap& map, Trajectory& gt, int n) {
  std::uint64_t id = 0;
  auto add = [&](double x, double y, double phi) {
    const StampNs t = static_cast<StampNs>(id + 1) * 250'000'000;
    gt.push_back({t, TPose2D(x, y, phi)});
    Keyframe kf;
    kf.id = id++;
    kf.stamp_ns = t;
    kf.pose = TPose2D(x, y, phi);
    map.keyframes.push_back(kf);
  };
  for (int i = 0; i < n; ++i) add(4.0 * i, 0, 0);
  for (int i = n - 1; i >= 0; --i) add(4.0 * i, 5, M_PI);
}

/// Keyframe `query` (return leg) in keyframe `match`'s frame (out leg), off the truth by (ex, ey)
/// in the match's frame.
LoopRecord loop(std::uint64_t query, std::uint64_t match, int n, double ex, double ey) {
  LoopRecord l;
  l.query = query;
  l.match = match;
  l.accepted = true;
  const double dx = 4.0 * (2 * n - 1 - static_cast<int>(query)) - 4.0 * static_cast<int>(match);
  l.relative = TPose2D(dx + ex, 5 + ey, M_PI);
  l.information = Eigen::Vector3d(25, 25, 3283).asDiagonal();
  return l;
}

TEST(LoopEvaluation, APartialLoopIsJudgedAcrossItsLineOnly) {
  KeyframeMap map;
  Trajectory gt;
  const int n = 60;
  outAndBack(map, gt, n);
  // The street runs along the match's x; in the query's frame (heading pi) that is x as well.
  LoopRecord slid = loop(2 * n - 1 - 10, 10, n, 25.0, 0.1);  // 25 m along: not a claim it makes
  slid.slide = true;
  slid.slide_direction = Eigen::Vector2d(1, 0);
  LoopRecord across = loop(2 * n - 1 - 20, 20, n, 0.0, 2.5);  // 2.5 m across: false
  across.slide = true;
  across.slide_direction = Eigen::Vector2d(1, 0);
  const LoopRecord full = loop(2 * n - 1 - 30, 30, n, 0.1, 0.1);
  const LoopRecord full_off = loop(2 * n - 1 - 40, 40, n, 25.0, 0.1);  // a full loop 25 m off: false

  const LoopEvaluation ev = evaluateLoops(map, {slid, across, full, full_off}, gt);
  EXPECT_EQ(ev.accepted, 4u);
  EXPECT_EQ(ev.slide_accepted, 2u);
  EXPECT_EQ(ev.slide_false, 1u);
  EXPECT_EQ(ev.false_accepted, 2u);  // the partial loop 2.5 m across and the full loop 25 m off
  EXPECT_EQ(ev.false_in_graph, 2u);
  EXPECT_EQ(ev.keyframes_with_loop_found, 1u) << "only the correct full loop counts as found";
  EXPECT_NEAR(ev.max_error_m, std::hypot(0.1, 0.1), 1e-9);
}

TEST(LoopEvaluation, RefusedCandidatesAreJudgedByTheirPoseAndCountedByReason) {
  KeyframeMap map;
  Trajectory gt;
  const int n = 60;
  outAndBack(map, gt, n);
  auto refused = [&](std::uint64_t match, double ex, const std::string& reason) {
    LoopRecord l = loop(2 * n - 1 - match, match, n, ex, 0.0);
    l.accepted = false;
    l.reason = reason;
    return l;
  };
  const std::vector<LoopRecord> loops = {
      refused(10, 0.5, "ambiguous place (a distant alignment scores almost as well)"),
      refused(12, 1.5, "ambiguous place (a distant alignment scores almost as well)"),
      refused(14, 8.0, "ambiguous place (a distant alignment scores almost as well)"),  // wrong pose
      refused(16, 0.2, "beyond the drift bound (91.4 m)"),
      refused(18, 30.0, "too few inliers"),    // wrong pose
      loop(2 * n - 1 - 30, 30, n, 0.1, 0.1)};  // accepted: not a refusal
  const LoopEvaluation ev = evaluateLoops(map, loops, gt);
  EXPECT_EQ(ev.accepted, 1u);
  EXPECT_EQ(ev.refused_wrong, 2u);
  ASSERT_EQ(ev.refused_right.size(), 2u);
  EXPECT_EQ(ev.refused_right.at("ambiguous place"), 2u);
  EXPECT_EQ(ev.refused_right.at("beyond the drift bound"), 1u);
  EXPECT_EQ(refusedRightText(ev), "2 ambiguous place, 1 beyond the drift bound");
  EXPECT_EQ(refusedRightText(LoopEvaluation{}), "none");
}

}  // namespace
}  // namespace radarslam
