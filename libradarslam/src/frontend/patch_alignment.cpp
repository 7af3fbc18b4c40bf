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

/// Samples `m` bilinearly on the (2h+1)^2 unit grid centred at `p`, row-major into `out`. Every
/// sample shares p's fractional offset, so the four weights are computed once.
void sampleGrid(const cv::Mat& m, cv::Point2f p, int h, float* out) {
  const int x0 = static_cast<int>(std::floor(p.x)), y0 = static_cast<int>(std::floor(p.y));
  const float fx = p.x - static_cast<float>(x0), fy = p.y - static_cast<float>(y0);
  const float w00 = (1 - fx) * (1 - fy), w01 = fx * (1 - fy), w10 = (1 - fx) * fy, w11 = fx * fy;
  for (int dy = -h; dy <= h; ++dy) {
    const float* r0 = m.ptr<float>(y0 + dy) + x0;
    const float* r1 = m.ptr<float>(y0 + dy + 1) + x0;
    for (int dx = -h; dx <= h; ++dx)
      *out++ = w00 * r0[dx] + w01 * r0[dx + 1] + w10 * r1[dx] + w11 * r1[dx + 1];
  }
}

/// dot[oy * O + ox] += sum over the template of t * cur at offset (ox, oy) from (x0, y0), summed
/// in the same order as the general loop (row by row of the template), with O x O sums held in
/// local variables instead of memory.
template <int O>
void accumulateDots(const float* t, const cv::Mat& cur, int x0, int y0, int n, double* dot) {
  double d[O * O] = {};
  for (int ty = 0; ty < n; ++ty) {
    const float* rows[O];
    for (int oy = 0; oy < O; ++oy) rows[oy] = cur.ptr<float>(y0 + ty + oy) + x0;
    for (int tx = 0; tx < n; ++tx) {
      const double tv = t[ty * n + tx];
      for (int oy = 0; oy < O; ++oy)
        for (int ox = 0; ox < O; ++ox) d[oy * O + ox] += tv * rows[oy][tx + ox];
    }
  }
  for (int i = 0; i < O * O; ++i) dot[i] += d[i];
}

/// Zero-mean NCC of the template `t` ((2r+1)^2, zero mean, squared norm tn) with `cur` at every
/// integer offset within s of (cx, cy); returns the best score and offset. Window sums come from
/// a summed-area table; the dot products accumulate per offset, so no long dependency chains.
double bestIntegerOffset(const std::vector<float>& t, double tn, const cv::Mat& cur, int cx, int cy, int r,
                         int s, int& bx, int& by) {
  const int n = 2 * r + 1, o = 2 * s + 1, w = n + o - 1;  // region w x w around (cx, cy)
  thread_local std::vector<double> sat, sat2, dot;
  sat.assign(static_cast<std::size_t>((w + 1) * (w + 1)), 0.0);
  sat2.assign(sat.size(), 0.0);
  dot.assign(static_cast<std::size_t>(o * o), 0.0);
  for (int y = 0; y < w; ++y) {
    const float* row = cur.ptr<float>(cy - s - r + y) + (cx - s - r);
    double rs = 0, rs2 = 0;
    for (int x = 0; x < w; ++x) {
      rs += row[x];
      rs2 += static_cast<double>(row[x]) * row[x];
      const std::size_t i = static_cast<std::size_t>((y + 1) * (w + 1) + x + 1);
      sat[i] = sat[i - static_cast<std::size_t>(w + 1)] + rs;
      sat2[i] = sat2[i - static_cast<std::size_t>(w + 1)] + rs2;
    }
  }
  if (o == 3)  // the tracking search (s = 1): the nine sums stay in registers
    accumulateDots<3>(t.data(), cur, cx - s - r, cy - s - r, n, dot.data());
  else if (o == 5)  // the inliers' search (s = 2)
    accumulateDots<5>(t.data(), cur, cx - s - r, cy - s - r, n, dot.data());
  else
    for (int ty = 0; ty < n; ++ty)
      for (int tx = 0; tx < n; ++tx) {
        const double tv = t[static_cast<std::size_t>(ty * n + tx)];
        for (int oy = 0; oy < o; ++oy) {
          const float* row = cur.ptr<float>(cy - s - r + ty + oy) + (cx - s - r + tx);
          double* d = dot.data() + oy * o;
          for (int ox = 0; ox < o; ++ox) d[ox] += tv * row[ox];
        }
      }
  const double cnt = static_cast<double>(n * n);
  auto rect = [&](const std::vector<double>& a, int x, int y) {  // sum over [x, x+n) x [y, y+n)
    const auto at = [&](int yy, int xx) { return a[static_cast<std::size_t>(yy * (w + 1) + xx)]; };
    return at(y + n, x + n) - at(y, x + n) - at(y + n, x) + at(y, x);
  };
  double best = -2;
  for (int oy = 0; oy < o; ++oy)
    for (int ox = 0; ox < o; ++ox) {
      const double sum = rect(sat, ox, oy), var = rect(sat2, ox, oy) - sum * sum / cnt;
      // t is zero-mean, so sum(t) * mean(cur) vanishes from the dot product.
      const double c = (var <= 1e-9 || tn <= 1e-9)
                           ? -1.0
                           : dot[static_cast<std::size_t>(oy * o + ox)] / std::sqrt(var * tn);
      if (c > best) {
        best = c;
        bx = ox - s;
        by = oy - s;
      }
    }
  return best;
}

}  // namespace

PatchAlignResult alignPatch(const AlignImage& ref, cv::Point2f ref_pt, const AlignImage& cur,
                            cv::Point2f cur_pt, const PatchAlignParams& params) {
  PatchAlignResult out;
  out.position = cur_pt;
  const int r = params.patch_radius_px, s = params.search_radius_px;
  if (r < 1 || s < 0) return out;  // not a patch (loadParams refuses these; direct callers too)
  const int margin = r + s + 2;
  const int rx = cvRound(ref_pt.x), ry = cvRound(ref_pt.y);
  const int cx = cvRound(cur_pt.x), cy = cvRound(cur_pt.y);
  auto inside = [&](const cv::Mat& m, int x, int y) {
    return x >= margin && y >= margin && x < m.cols - margin && y < m.rows - margin;
  };
  if (!inside(ref.smooth, rx, ry) || !inside(cur.smooth, cx, cy)) return out;

  // Template sampled at the sub-pixel reference keypoint, with a one-pixel border for gradients.
  const int n = 2 * r + 1, ne = n + 2;
  // Scratch reused across calls (thousands per scan): no allocation once the sizes are reached.
  thread_local std::vector<float> ext, t, tgx, tgy, cur_patch;
  ext.resize(static_cast<std::size_t>(ne * ne));
  t.resize(static_cast<std::size_t>(n * n));
  sampleGrid(ref.smooth, ref_pt, r + 1, ext.data());
  auto ext_at = [&](int y, int x) { return ext[static_cast<std::size_t>((y + 1) * ne + x + 1)]; };
  double mean = 0;
  for (int y = 0, k = 0; y < n; ++y)
    for (int x = 0; x < n; ++x, ++k) mean += t[static_cast<std::size_t>(k)] = ext_at(y, x);
  mean /= n * n;
  double tn = 0;  // summed in a local, not through memory (a store-to-load chain per pixel)
  for (std::size_t k = 0; k < t.size(); ++k) {
    const float v = static_cast<float>(t[k] - mean);
    t[k] = v;
    tn += static_cast<double>(v) * v;
  }

  // 1. Exhaustive integer search.
  int bx = 0, by = 0;
  const double best = bestIntegerOffset(t, tn, cur.smooth, cx, cy, r, s, bx, by);
  out.ncc = best;
  if (best < params.min_ncc) return out;

  // 2. Translational Lucas-Kanade from the best integer offset, inverse compositional (template
  //    gradients and Hessian computed once), on zero-mean, contrast-matched patches.
  tgx.resize(t.size());
  tgy.resize(t.size());
  double h00 = 0, h01 = 0, h11 = 0;
  for (int y = 0, k = 0; y < n; ++y)
    for (int x = 0; x < n; ++x, ++k) {
      // Template gradient by central differences (only the template's pixels need one).
      tgx[k] = 0.5f * (ext_at(y, x + 1) - ext_at(y, x - 1));
      tgy[k] = 0.5f * (ext_at(y + 1, x) - ext_at(y - 1, x));
      h00 += static_cast<double>(tgx[k]) * tgx[k];
      h01 += static_cast<double>(tgx[k]) * tgy[k];
      h11 += static_cast<double>(tgy[k]) * tgy[k];
    }
  const double det = h00 * h11 - h01 * h01;
  float px = static_cast<float>(cx + bx), py = static_cast<float>(cy + by);
  cur_patch.resize(t.size());
  for (int it = 0; it < params.lk_iterations && det > 1e-9; ++it) {
    sampleGrid(cur.smooth, {px, py}, r, cur_patch.data());
    double cm = 0;
    for (float v : cur_patch) cm += v;
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
