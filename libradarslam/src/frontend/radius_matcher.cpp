#include "radarslam/frontend/radius_matcher.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace radarslam {

namespace {

double descriptorDistance(const cv::Mat& a, int ia, const cv::Mat& b, int ib, int norm_type) {
  if (norm_type == cv::NORM_HAMMING || norm_type == cv::NORM_HAMMING2) {
    const std::uint8_t* pa = a.ptr<std::uint8_t>(ia);
    const std::uint8_t* pb = b.ptr<std::uint8_t>(ib);
    int d = 0, k = 0;
    const int n = a.cols;
    for (; k + 8 <= n; k += 8) {
      std::uint64_t x, y;
      std::memcpy(&x, pa + k, 8);
      std::memcpy(&y, pb + k, 8);
      d += std::popcount(x ^ y);
    }
    for (; k < n; ++k) d += std::popcount(static_cast<unsigned>(pa[k] ^ pb[k]));
    return d;
  }
  return cv::norm(a.row(ia), b.row(ib), cv::NORM_L2);
}

/// Uniform grid over the reference points for radius queries.
class Grid {
 public:
  Grid(const std::vector<Eigen::Vector2d>& pts, double cell) : cell_(cell) {
    for (int i = 0; i < static_cast<int>(pts.size()); ++i)
      cells_[key(cellOf(pts[i].x()), cellOf(pts[i].y()))].push_back(i);
  }
  template <typename F>
  void forEachNear(const Eigen::Vector2d& q, F&& f) const {
    const long cx = cellOf(q.x()), cy = cellOf(q.y());
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (int i : it->second) f(i);
      }
  }

 private:
  long cellOf(double v) const { return static_cast<long>(std::floor(v / cell_)); }
  static long long key(long x, long y) { return (static_cast<long long>(x) << 32) ^ (y & 0xffffffffLL); }
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

struct Best {
  int index = -1;
  double d1 = std::numeric_limits<double>::max(), d2 = std::numeric_limits<double>::max();
};

}  // namespace

double SearchRadius::at(double range_m) const {
  return std::min(max_m, std::hypot(fixed_m, per_range * range_m));
}

Correspondences matchWithinRadius(const FeatureSet& cur, const FeatureSet& ref,
                                  const mrpt::math::TPose2D& prior, double radius_m,
                                  const MatchParams& params) {
  return matchWithinRadius(cur, ref, prior, SearchRadius::fixed(radius_m), params);
}

Correspondences matchWithinRadius(const FeatureSet& cur, const FeatureSet& ref,
                                  const mrpt::math::TPose2D& prior, const SearchRadius& radius,
                                  const MatchParams& params) {
  Correspondences out;
  if (cur.xy.empty() || ref.xy.empty()) return out;
  const bool binary = cur.norm_type == cv::NORM_HAMMING || cur.norm_type == cv::NORM_HAMMING2;
  const double c = std::cos(prior.phi), s = std::sin(prior.phi);
  std::vector<Eigen::Vector2d> predicted(cur.xy.size());
  std::vector<double> r2(cur.xy.size());
  double cell = 0.0;
  for (std::size_t i = 0; i < cur.xy.size(); ++i) {
    const auto& p = cur.xy[i];
    predicted[i] = {c * p.x() - s * p.y() + prior.x, s * p.x() + c * p.y() + prior.y};
    const double r = radius.at(p.norm());
    r2[i] = r * r;
    cell = std::max(cell, r);
  }
  if (!(cell > 0)) return out;
  const Grid grid(ref.xy, cell);
  std::vector<Best> fwd(cur.xy.size());
  std::vector<Best> bwd(ref.xy.size());
  for (std::size_t i = 0; i < cur.xy.size(); ++i) {
    grid.forEachNear(predicted[i], [&](int j) {
      if ((ref.xy[j] - predicted[i]).squaredNorm() > r2[i]) return;
      const double d =
          descriptorDistance(cur.descriptors, static_cast<int>(i), ref.descriptors, j, cur.norm_type);
      auto upd = [d](Best& b, int idx) {
        if (d < b.d1) {
          b.d2 = b.d1;
          b.d1 = d;
          b.index = idx;
        } else if (d < b.d2) {
          b.d2 = d;
        }
      };
      upd(fwd[i], j);
      upd(bwd[j], static_cast<int>(i));
    });
  }
  for (std::size_t i = 0; i < cur.xy.size(); ++i) {
    const Best& b = fwd[i];
    if (b.index < 0) continue;
    if (binary && b.d1 > params.max_descriptor_distance) continue;
    if (params.ratio < 1.0 && b.d2 < std::numeric_limits<double>::max() && b.d1 > params.ratio * b.d2)
      continue;
    if (params.mutual && bwd[b.index].index != static_cast<int>(i)) continue;
    Correspondence m;
    m.cur = cur.xy[i];
    m.ref = ref.xy[b.index];
    m.descriptor_distance = b.d1;
    m.cur_index = static_cast<int>(i);
    m.ref_index = b.index;
    out.push_back(m);
  }
  return out;
}

}  // namespace radarslam
