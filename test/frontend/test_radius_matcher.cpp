#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <random>

#include "radarslam/frontend/keyframe_policy.h"
#include "radarslam/frontend/radius_matcher.h"

namespace radarslam {
namespace {

struct Scene {
  FeatureSet cur, ref;
};

/// ref = truth (+) cur for every point; descriptors equal up to a few flipped bits.
Scene makeScene(const mrpt::math::TPose2D& truth, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-60, 60);
  std::uniform_int_distribution<int> byte(0, 255), bit(0, 255);
  Scene s;
  s.cur.descriptors.create(n, 32, CV_8U);
  s.ref.descriptors.create(n, 32, CV_8U);
  s.cur.norm_type = s.ref.norm_type = cv::NORM_HAMMING;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d c(u(rng), u(rng));
    const auto r = truth.composePoint({c.x(), c.y()});
    s.cur.xy.push_back(c);
    s.ref.xy.emplace_back(r.x, r.y);
    for (int k = 0; k < 32; ++k)
      s.ref.descriptors.at<uchar>(i, k) = s.cur.descriptors.at<uchar>(i, k) = byte(rng);
    for (int f = 0; f < 5; ++f) {
      const int b = bit(rng);
      s.cur.descriptors.at<uchar>(i, b / 8) ^= static_cast<uchar>(1 << (b % 8));
    }
  }
  return s;
}

TEST(RadiusMatcher, FindsTrueMatchesAroundThePrior) {
  const mrpt::math::TPose2D truth(2.2, 0.1, 0.01);
  const Scene s = makeScene(truth, 300, 1);
  MatchParams p;
  const Correspondences m = matchWithinRadius(s.cur, s.ref, {2.0, 0.0, 0.0}, 2.0, p);  // prior 0.2 m off
  EXPECT_GE(m.size(), 290u);
  for (const auto& c : m) EXPECT_EQ(c.cur_index, c.ref_index);
}

TEST(RadiusMatcher, IgnoresIdenticalDescriptorsOutsideTheRadius) {
  const mrpt::math::TPose2D truth(0, 0, 0);
  Scene s = makeScene(truth, 50, 2);
  // A decoy with a perfect descriptor 10 m from point 0 must lose to the true point inside 2 m.
  s.ref.xy.push_back(s.ref.xy[0] + Eigen::Vector2d(10, 0));
  cv::Mat row = s.cur.descriptors.row(0).clone();
  s.ref.descriptors.push_back(row);
  MatchParams p;
  p.ratio = 1.0;
  const Correspondences m = matchWithinRadius(s.cur, s.ref, truth, 2.0, p);
  for (const auto& c : m) EXPECT_NE(c.ref_index, 50);
  // A prior further off than the radius finds nothing.
  EXPECT_TRUE(matchWithinRadius(s.cur, s.ref, {30.0, 0.0, 0.0}, 2.0, p).empty());
}

TEST(RadiusMatcher, RangeDependentRadiusFollowsAHeadingError) {
  // The truth is the prior turned by 2 degrees: a point at range rho is rho * 0.035 m off its
  // prediction. A radius that grows with range finds the far points a fixed 1 m radius misses.
  const mrpt::math::TPose2D prior(1.0, 0.0, 0.0), truth(1.0, 0.0, 2.0 * M_PI / 180.0);
  const Scene s = makeScene(truth, 300, 3);
  MatchParams p;
  int far_fixed = 0, far_adaptive = 0;
  for (const auto& c : matchWithinRadius(s.cur, s.ref, prior, 1.0, p))
    far_fixed += s.cur.xy[c.cur_index].norm() > 40;
  const SearchRadius grows{1.0, 3.0 * 2.0 * M_PI / 180.0, 12.5};
  const Correspondences m = matchWithinRadius(s.cur, s.ref, prior, grows, p);
  for (const auto& c : m) {
    EXPECT_EQ(c.cur_index, c.ref_index);
    far_adaptive += s.cur.xy[c.cur_index].norm() > 40;
  }
  EXPECT_EQ(far_fixed, 0);
  EXPECT_GE(far_adaptive, 30);
}

TEST(SearchRadius, GrowsWithRangeUpToTheCap) {
  const SearchRadius r{1.0, 0.05, 4.0};
  EXPECT_DOUBLE_EQ(r.at(0.0), 1.0);
  EXPECT_NEAR(r.at(20.0), std::sqrt(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(r.at(200.0), 4.0);
}

TEST(KeyframePolicy, TranslationRotationAndMatchCount) {
  KeyframeParams p;
  p.max_translation_m = 2.0;  // the authors' configuration
  p.max_rotation_rad = 0.2;
  p.min_inliers = 60;
  EXPECT_FALSE(needNewKeyframe(p, {1.0, 0.5, 0.05}, 200));
  EXPECT_TRUE(needNewKeyframe(p, {2.1, 0.0, 0.0}, 200));
  EXPECT_TRUE(needNewKeyframe(p, {0.1, 0.0, -0.21}, 200));
  EXPECT_TRUE(needNewKeyframe(p, {0.1, 0.0, 0.0}, 10));
}

}  // namespace
}  // namespace radarslam
