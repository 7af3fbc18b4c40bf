#include "radarslam/eval/kitti_metric.h"

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace radarslam::eval {

std::vector<double> cumulativeDistances(const std::vector<mrpt::math::TPose2D>& poses) {
  std::vector<double> dist(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i)
    dist[i] = dist[i - 1] + std::hypot(poses[i].x - poses[i - 1].x, poses[i].y - poses[i - 1].y);
  return dist;
}

KittiResult computeKittiMetric(const std::vector<mrpt::math::TPose2D>& gt,
                               const std::vector<mrpt::math::TPose2D>& est, const KittiParams& params) {
  if (gt.size() != est.size()) throw std::invalid_argument("computeKittiMetric: gt and est differ in size");
  if (params.step_frames == 0) throw std::invalid_argument("computeKittiMetric: step_frames must be >= 1");
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kDeg = 180.0 / std::numbers::pi;
  KittiResult r;
  const std::vector<double> dist = cumulativeDistances(gt);
  std::vector<double> t_sum(params.lengths_m.size(), 0.0), r_sum(params.lengths_m.size(), 0.0);
  std::vector<std::size_t> count(params.lengths_m.size(), 0);

  for (std::size_t first = 0; first < gt.size(); first += params.step_frames) {
    for (std::size_t k = 0; k < params.lengths_m.size(); ++k) {
      const double len = params.lengths_m[k];
      // Devkit lastFrameFromSegmentLength: the first frame with dist > dist[first] + len (strictly).
      const auto it =
          std::upper_bound(dist.begin() + static_cast<std::ptrdiff_t>(first), dist.end(), dist[first] + len);
      if (it == dist.end()) continue;
      const std::size_t last = static_cast<std::size_t>(it - dist.begin());
      // TPose2D: b - a = inv(a) (+) b.
      const mrpt::math::TPose2D d_gt = gt[last] - gt[first];
      const mrpt::math::TPose2D d_est = est[last] - est[first];
      const mrpt::math::TPose2D e = d_est - d_gt;  // inv(dGT) (+) dEst
      KittiSegment s;
      s.first = first, s.last = last, s.length_m = len;
      s.t_err = std::hypot(e.x, e.y) / len;
      s.r_err_rad_per_m = std::abs(mrpt::math::wrapToPi(e.phi)) / len;
      r.segment_errors.push_back(s);
      t_sum[k] += s.t_err, r_sum[k] += s.r_err_rad_per_m, ++count[k];
    }
  }

  double t_all = 0, r_all = 0;
  for (const auto& s : r.segment_errors) t_all += s.t_err, r_all += s.r_err_rad_per_m;
  r.segments = r.segment_errors.size();
  const double n = static_cast<double>(r.segments);
  r.t_err_percent = r.segments ? 100.0 * t_all / n : kNaN;
  r.r_err_deg_per_m = r.segments ? kDeg * r_all / n : kNaN;
  r.r_err_deg_per_100m = r.segments ? 100.0 * kDeg * r_all / n : kNaN;
  for (std::size_t k = 0; k < params.lengths_m.size(); ++k) {
    KittiLengthStats l;
    l.length_m = params.lengths_m[k];
    l.segments = count[k];
    const double c = static_cast<double>(count[k]);
    l.t_err_percent = count[k] ? 100.0 * t_sum[k] / c : kNaN;
    l.r_err_deg_per_100m = count[k] ? 100.0 * kDeg * r_sum[k] / c : kNaN;
    r.per_length.push_back(l);
  }
  return r;
}

}  // namespace radarslam::eval
