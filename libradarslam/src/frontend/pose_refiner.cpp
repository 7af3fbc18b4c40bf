#include "radarslam/frontend/pose_refiner.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace radarslam {

namespace {
/// Information matrix of a match, scaled so that a purely radial residual keeps its metres.
Eigen::Matrix2d information(const Correspondence& m, const RefineParams& p) {
  if (!(p.azimuth_sigma_rad > 0)) return Eigen::Matrix2d::Identity();
  const double r = m.ref.norm();
  if (r < 1e-6) return Eigen::Matrix2d::Identity();
  const Eigen::Vector2d u = m.ref / r;  // along the beam
  const Eigen::Vector2d t(-u.y(), u.x());
  const double st = std::max(r * p.azimuth_sigma_rad, p.range_sigma_m);
  const double ratio = (p.range_sigma_m * p.range_sigma_m) / (st * st);
  return u * u.transpose() + ratio * t * t.transpose();
}
}  // namespace

RefineResult refinePose(const Correspondences& matches, const mrpt::math::TPose2D& initial,
                        const RefineParams& params, std::span<const Eigen::Matrix2d> shapes) {
  RefineResult out;
  out.pose = initial;
  if (matches.size() < 2) return out;
  const bool shaped = shapes.size() == matches.size();
  double x = initial.x, y = initial.y, th = initial.phi;
  for (int it = 0; it < params.iterations; ++it) {
    const double c = std::cos(th), s = std::sin(th);
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < matches.size(); ++i) {
      const Correspondence& m = matches[i];
      const double px = m.cur.x(), py = m.cur.y();
      const Eigen::Vector2d r(m.ref.x() - (c * px - s * py + x), m.ref.y() - (s * px + c * py + y));
      const Eigen::Matrix2d W = shaped ? shapes[i] : information(m, params);
      const double e = std::sqrt(r.dot(W * r));
      const double w = m.weight * (e <= params.huber_m ? 1.0 : params.huber_m / e);
      // d(T (+) p)/d(x, y, th)
      Eigen::Matrix<double, 2, 3> J;
      J << 1, 0, -s * px - c * py, 0, 1, c * px - s * py;
      H += w * J.transpose() * W * J;
      b += w * J.transpose() * W * r;
    }
    const Eigen::Vector3d delta = H.ldlt().solve(b);
    if (!delta.allFinite()) break;
    x += delta.x();
    y += delta.y();
    th += delta.z();
    out.iterations = it + 1;
    if (delta.head<2>().norm() < 1e-6 && std::abs(delta.z()) < 1e-8) break;
  }
  out.pose = mrpt::math::TPose2D(x, y, std::remainder(th, 2.0 * M_PI));
  const double c = std::cos(th), s = std::sin(th);
  double sw = 0, se = 0;
  for (const auto& m : matches) {
    const Eigen::Vector2d r(m.ref.x() - (c * m.cur.x() - s * m.cur.y() + x),
                            m.ref.y() - (s * m.cur.x() + c * m.cur.y() + y));
    sw += m.weight;
    se += m.weight * r.squaredNorm();
  }
  out.rms_m = sw > 0 ? std::sqrt(se / sw) : 0.0;
  return out;
}

}  // namespace radarslam
