// Sub-pixel patch alignment (frontend/patch_alignment.h): the exhaustive integer search finds the
// NCC maximum for every search radius, Lucas-Kanade recovers a sub-pixel shift, and patches that
// do not correlate or do not fit in the image are reported as not aligned.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "radarslam/frontend/patch_alignment.h"

namespace radarslam {
namespace {

/// Bright Gaussian blobs of random size on a dark 8-bit background (a radar-like texture).
cv::Mat blobImage(unsigned seed, int size = 160) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0, size), sigma(1.2, 3.5), level(60, 250);
  cv::Mat f(size, size, CV_32F, cv::Scalar(0));
  for (int k = 0; k < 220; ++k) {
    const double cx = pos(rng), cy = pos(rng), s = sigma(rng), a = level(rng);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
        if (d2 < 25 * s * s) f.at<float>(y, x) += static_cast<float>(a * std::exp(-d2 / (2 * s * s)));
      }
  }
  cv::Mat out;
  f.convertTo(out, CV_8U);  // saturates at 255
  return out;
}

/// `image` moved by (dx, dy): what was at p is at p + (dx, dy).
cv::Mat shifted(const cv::Mat& image, double dx, double dy) {
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::Mat out;
  cv::warpAffine(image, out, m, image.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return out;
}

/// Zero-mean NCC of the (2r+1)^2 patch of `a` at (ax, ay) with that of `b` at (bx, by).
double ncc(const cv::Mat& a, int ax, int ay, const cv::Mat& b, int bx, int by, int r) {
  const cv::Rect ra(ax - r, ay - r, 2 * r + 1, 2 * r + 1), rb(bx - r, by - r, 2 * r + 1, 2 * r + 1);
  cv::Mat pa, pb;
  a(ra).convertTo(pa, CV_64F);
  b(rb).convertTo(pb, CV_64F);
  pa -= cv::mean(pa)[0];
  pb -= cv::mean(pb)[0];
  return pa.dot(pb) / std::sqrt(pa.dot(pa) * pb.dot(pb));
}

TEST(PatchAlignment, IntegerSearchFindsTheNccMaximumForEverySearchRadius) {
  // Without Lucas-Kanade steps the answer is the best integer offset; it must be the argmax of a
  // direct NCC over the same offsets (the search radii 1 and 2 of the defaults have their own
  // accumulation code, the others the general one).
  PatchAlignParams params;
  params.lk_iterations = 0;
  params.min_ncc = -1;
  params.blur_sigma_px = 0;  // the smoothed image is the image itself, so the direct NCC can use it
  const cv::Mat ref8 = blobImage(3), cur8 = shifted(ref8, 1.0, -2.0);
  const AlignImage ref = prepareAlignImage(ref8, params), cur = prepareAlignImage(cur8, params);
  int checked = 0;
  for (int s = 0; s <= 4; ++s) {
    params.search_radius_px = s;
    for (int y = 40; y <= 120; y += 20)
      for (int x = 40; x <= 120; x += 20) {
        const cv::Point2f start(static_cast<float>(x + 1), static_cast<float>(y - 1));
        const PatchAlignResult a =
            alignPatch(ref, {static_cast<float>(x), static_cast<float>(y)}, cur, start, params);
        double best = -2;
        int bx = 0, by = 0;
        for (int oy = -s; oy <= s; ++oy)
          for (int ox = -s; ox <= s; ++ox) {
            const double c =
                ncc(ref.smooth, x, y, cur.smooth, x + 1 + ox, y - 1 + oy, params.patch_radius_px);
            if (c > best) best = c, bx = ox, by = oy;
          }
        ASSERT_TRUE(a.ok) << "s " << s << " at " << x << ", " << y;
        EXPECT_NEAR(a.ncc, best, 1e-6) << "s " << s << " at " << x << ", " << y;
        EXPECT_EQ(a.position, cv::Point2f(static_cast<float>(x + 1 + bx), static_cast<float>(y - 1 + by)))
            << "s " << s << " at " << x << ", " << y;
        ++checked;
      }
  }
  EXPECT_EQ(checked, 5 * 25);
}

TEST(PatchAlignment, LucasKanadeRecoversASubPixelShift) {
  const PatchAlignParams params;  // defaults: blur, search radius 2, 3 LK steps
  const double dx = 1.3, dy = -0.6;
  const cv::Mat ref8 = blobImage(7), cur8 = shifted(ref8, dx, dy);
  const AlignImage ref = prepareAlignImage(ref8, params), cur = prepareAlignImage(cur8, params);
  std::vector<double> errors;
  for (int y = 40; y <= 120; y += 10)
    for (int x = 40; x <= 120; x += 10) {
      const cv::Point2f p(x + 0.25f, y + 0.5f);
      const PatchAlignResult a = alignPatch(ref, p, cur, p, params);  // start at the unshifted place
      if (a.ok) errors.push_back(std::hypot(a.position.x - (p.x + dx), a.position.y - (p.y + dy)));
    }
  ASSERT_GE(errors.size(), 70u);  // of 81 (flat background patches may not correlate)
  std::sort(errors.begin(), errors.end());
  // In pixels; the best integer offset alone is 0.5 px off here (0.3 and 0.4 per axis). The
  // shifted image is itself interpolated (cubic), and a patch may stop in a local minimum.
  EXPECT_LT(errors[errors.size() / 2], 0.1);
  EXPECT_LT(errors[errors.size() * 9 / 10], 0.25);
}

TEST(PatchAlignment, UncorrelatedOrOutsidePatchesAreNotAligned) {
  const PatchAlignParams params;
  const cv::Mat ref8 = blobImage(11), other8 = blobImage(12);
  const AlignImage ref = prepareAlignImage(ref8, params), other = prepareAlignImage(other8, params);
  int refused = 0, total = 0;
  for (int y = 40; y <= 120; y += 20)
    for (int x = 40; x <= 120; x += 20) {
      const cv::Point2f p(static_cast<float>(x), static_cast<float>(y));
      const PatchAlignResult a = alignPatch(ref, p, other, p, params);
      ++total;
      if (!a.ok) {
        ++refused;
        EXPECT_EQ(a.position, p);  // left where it was
        EXPECT_LT(a.ncc, params.min_ncc);
      }
    }
  EXPECT_GE(refused, total * 3 / 4);  // another image: most patches find nothing above 0.6
  const cv::Point2f edge(3, 80), inside(80, 80);
  EXPECT_FALSE(alignPatch(ref, edge, ref, inside, params).ok);
  EXPECT_FALSE(alignPatch(ref, inside, ref, edge, params).ok);
  EXPECT_TRUE(alignPatch(ref, inside, ref, inside, params).ok);
}

}  // namespace
}  // namespace radarslam
