#include "radarslam/frontend/patch_alignment.h"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <vector>

namespace radarslam {

AlignImage prepareAlignImage(const cv::Mat& image8u, const PatchAlignParams& params) {
  AlignImage a;
  cv::Mat blurred = image8u;
  if (params.blur_sigma_px > 0) {
    const int k = 2 * static_cast<int>(std::ceil(2.5 * params.blur_sigma_px)) + 1;
    cv::GaussianBlur(image8u, blurred, cv::Size(k, k), params.blur_sigma_px);  // fast fixed-point 8-bit path
  }
  blurred.convertTo(a.smooth, CV_32F);
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

  // 2. Translational Lucas-Kanade from the best integer offset, inverse compositional (template
  //    gradients and Hessian computed once), on zero-mean, contrast-matched patches.
  std::vector<float> tgx(t.size()), tgy(t.size());
  double h00 = 0, h01 = 0, h11 = 0;
  for (int dy = -r, k = 0; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx, ++k) {
      // Template gradient by central differences (only the template's pixels need one).
      const float x = ref_pt.x + dx, y = ref_pt.y + dy;
      tgx[k] = 0.5f * (bilinear(ref.smooth, x + 1, y) - bilinear(ref.smooth, x - 1, y));
      tgy[k] = 0.5f * (bilinear(ref.smooth, x, y + 1) - bilinear(ref.smooth, x, y - 1));
      h00 += static_cast<double>(tgx[k]) * tgx[k];
      h01 += static_cast<double>(tgx[k]) * tgy[k];
      h11 += static_cast<double>(tgy[k]) * tgy[k];
    }
  const double det = h00 * h11 - h01 * h01;
  float px = static_cast<float>(cx + bx), py = static_cast<float>(cy + by);
  std::vector<float> cur_patch(t.size());
  for (int it = 0; it < params.lk_iterations && det > 1e-9; ++it) {
    double cm = 0;
    for (int dy = -r, k = 0; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx, ++k) cm += cur_patch[k] = bilinear(cur.smooth, px + dx, py + dy);
    cm /= n * n;
    double cn = 0;
    for (float v : cur_patch) cn += (v - cm) * (v - cm);
    const double gain = cn > 1e-9 ? std::sqrt(tn / cn) : 1.0;  // match the template's contrast
    double b0 = 0, b1 = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double e = gain * (cur_patch[k] - cm) - t[k];
      b0 += tgx[k] * e;
      b1 += tgy[k] * e;
    }
    // Template shifted by u matches the current patch: the patch lies at p - u.
    const double ux = (h11 * b0 - h01 * b1) / det, uy = (h00 * b1 - h01 * b0) / det;
    if (!std::isfinite(ux) || !std::isfinite(uy) || std::abs(ux) > 1.0 || std::abs(uy) > 1.0) break;
    px -= static_cast<float>(ux);
    py -= static_cast<float>(uy);
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
