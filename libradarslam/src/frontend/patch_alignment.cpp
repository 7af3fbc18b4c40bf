#include "radarslam/frontend/patch_alignment.h"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <vector>

namespace radarslam {

AlignImage prepareAlignImage(const cv::Mat& image8u, const PatchAlignParams& params) {
  AlignImage a;
  image8u.convertTo(a.smooth, CV_32F);
  if (params.blur_sigma_px > 0) cv::GaussianBlur(a.smooth, a.smooth, cv::Size(), params.blur_sigma_px);
  cv::Sobel(a.smooth, a.gx, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(a.smooth, a.gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  return a;
}

namespace {

inline float bilinear(const cv::Mat& m, float x, float y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const float fx = x - x0, fy = y - y0;
  const float* r0 = m.ptr<float>(y0);
  const float* r1 = m.ptr<float>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

/// Normalised cross-correlation of the zero-mean template `t` (norm tn) with cur at integer (cx, cy).
double nccAt(const std::vector<float>& t, double tn, const cv::Mat& cur, int cx, int cy, int r) {
  const int n = 2 * r + 1;
  double sum = 0, sum2 = 0, dot = 0;
  int k = 0;
  for (int dy = -r; dy <= r; ++dy) {
    const float* row = cur.ptr<float>(cy + dy) + cx - r;
    for (int dx = 0; dx < n; ++dx, ++k) {
      const double v = row[dx];
      sum += v;
      sum2 += v * v;
      dot += v * t[k];
    }
  }
  const double cnt = static_cast<double>(n * n);
  const double var = sum2 - sum * sum / cnt;
  if (var <= 1e-9 || tn <= 1e-9) return -1.0;
  return dot / std::sqrt(var * tn);  // t is zero-mean, so sum(t) * mean(cur) vanishes
}

}  // namespace

PatchAlignResult alignPatch(const AlignImage& ref, cv::Point2f ref_pt, const AlignImage& cur,
                            cv::Point2f cur_pt, const PatchAlignParams& params) {
  PatchAlignResult out;
  out.position = cur_pt;
  const int r = params.patch_radius_px, s = params.search_radius_px;
  const int margin = r + s + 2;
  const int rx = cvRound(ref_pt.x), ry = cvRound(ref_pt.y);
  const int cx = cvRound(cur_pt.x), cy = cvRound(cur_pt.y);
  auto inside = [&](const cv::Mat& m, int x, int y) {
    return x >= margin && y >= margin && x < m.cols - margin && y < m.rows - margin;
  };
  if (!inside(ref.smooth, rx, ry) || !inside(cur.smooth, cx, cy)) return out;

  // Template sampled at the sub-pixel reference keypoint.
  const int n = 2 * r + 1;
  std::vector<float> t(static_cast<std::size_t>(n * n));
  double mean = 0;
  for (int dy = -r, k = 0; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx, ++k) mean += t[k] = bilinear(ref.smooth, ref_pt.x + dx, ref_pt.y + dy);
  mean /= n * n;
  double tn = 0;
  for (float& v : t) {
    v = static_cast<float>(v - mean);
    tn += static_cast<double>(v) * v;
  }

  // 1. Exhaustive integer search.
  double best = -2;
  int bx = 0, by = 0;
  for (int oy = -s; oy <= s; ++oy)
    for (int ox = -s; ox <= s; ++ox) {
      const double c = nccAt(t, tn, cur.smooth, cx + ox, cy + oy, r);
      if (c > best) {
        best = c;
        bx = ox;
        by = oy;
      }
    }
  out.ncc = best;
  if (best < params.min_ncc) return out;

  // 2. Translational Lucas-Kanade from the best integer offset (gain/offset invariant via
  //    zero-mean patches).
  float px = static_cast<float>(cx + bx), py = static_cast<float>(cy + by);
  for (int it = 0; it < params.lk_iterations; ++it) {
    double h00 = 0, h01 = 0, h11 = 0, b0 = 0, b1 = 0, cm = 0;
    std::vector<float> cv(static_cast<std::size_t>(n * n));
    for (int dy = -r, k = 0; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx, ++k) cm += cv[k] = bilinear(cur.smooth, px + dx, py + dy);
    cm /= n * n;
    double cn = 0;
    for (float v : cv) cn += (v - cm) * (v - cm);
    const double gain = cn > 1e-9 ? std::sqrt(tn / cn) : 1.0;  // match the template's contrast
    for (int dy = -r, k = 0; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx, ++k) {
        const double gx = gain * bilinear(cur.gx, px + dx, py + dy);
        const double gy = gain * bilinear(cur.gy, px + dx, py + dy);
        const double e = t[k] - gain * (cv[k] - cm);
        h00 += gx * gx;
        h01 += gx * gy;
        h11 += gy * gy;
        b0 += gx * e;
        b1 += gy * e;
      }
    const double det = h00 * h11 - h01 * h01;
    if (det <= 1e-9) break;
    const double ux = (h11 * b0 - h01 * b1) / det, uy = (h00 * b1 - h01 * b0) / det;
    if (!std::isfinite(ux) || !std::isfinite(uy) || std::abs(ux) > 1.0 || std::abs(uy) > 1.0) break;
    px += static_cast<float>(ux);
    py += static_cast<float>(uy);
    if (std::hypot(px - (cx + bx), py - (cy + by)) > 1.5 || !inside(cur.smooth, cvRound(px), cvRound(py))) {
      px = static_cast<float>(cx + bx);
      py = static_cast<float>(cy + by);
      break;
    }
    if (ux * ux + uy * uy < 1e-4) break;
  }
  out.position = {px, py};
  out.ok = true;
  return out;
}

}  // namespace radarslam
