#include "radarslam/eval/pose_errors.h"

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "radarslam/eval/alignment.h"

namespace radarslam::eval {

namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;
}

ErrorStats computeStats(std::vector<double> v) {
  ErrorStats s;
  s.count = v.size();
  if (v.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.rmse = s.mean = s.median = s.std = s.min = s.max = nan;
    return s;
  }
  const double n = static_cast<double>(v.size());
  double sum = 0, sq = 0;
  for (double x : v) sum += x, sq += x * x;
  s.mean = sum / n;
  s.rmse = std::sqrt(sq / n);
  double var = 0;
  for (double x : v) var += (x - s.mean) * (x - s.mean);
  s.std = std::sqrt(var / n);
  std::sort(v.begin(), v.end());
  s.min = v.front();
  s.max = v.back();
  s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  return s;
}

AteResult computeAte(const std::vector<mrpt::math::TPose2D>& gt,
                     const std::vector<mrpt::math::TPose2D>& est) {
  if (gt.size() != est.size() || gt.empty())
    throw std::invalid_argument("computeAte: need matched, non-empty poses");
  std::vector<mrpt::math::TPoint2D> from, to;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    from.emplace_back(est[i].x, est[i].y);
    to.emplace_back(gt[i].x, gt[i].y);
  }
  AteResult r;
  r.alignment = alignSE2(from, to);
  std::vector<double> et, er;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    const mrpt::math::TPose2D a = r.alignment + est[i];
    r.est_aligned.push_back(a);
    et.push_back(std::hypot(a.x - gt[i].x, a.y - gt[i].y));
    er.push_back(std::abs(mrpt::math::wrapToPi(a.phi - gt[i].phi)) * kDeg);
  }
  r.trans_m = computeStats(std::move(et));
  r.rot_deg = computeStats(std::move(er));
  return r;
}

RpeResult computeRpe(const std::vector<mrpt::math::TPose2D>& gt,
                     const std::vector<mrpt::math::TPose2D>& est) {
  if (gt.size() != est.size()) throw std::invalid_argument("computeRpe: gt and est differ in size");
  RpeResult r;
  for (std::size_t i = 0; i + 1 < gt.size(); ++i) {
    const mrpt::math::TPose2D e = (est[i + 1] - est[i]) - (gt[i + 1] - gt[i]);  // inv(dGT) (+) dEst
    r.per_frame_trans_m.push_back(std::hypot(e.x, e.y));
    r.per_frame_rot_deg.push_back(std::abs(mrpt::math::wrapToPi(e.phi)) * kDeg);
  }
  r.trans_m = computeStats(r.per_frame_trans_m);
  r.rot_deg = computeStats(r.per_frame_rot_deg);
  return r;
}

}  // namespace radarslam::eval
