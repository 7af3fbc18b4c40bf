#include "radarslam/core/se2_covariance.h"

#include <cmath>

namespace radarslam {

Eigen::Matrix3d composeCovariance(const mrpt::math::TPose2D& a, const Eigen::Matrix3d& cov_a,
                                  const mrpt::math::TPose2D& b, const Eigen::Matrix3d& cov_b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  Eigen::Matrix3d ja = Eigen::Matrix3d::Identity();
  ja(0, 2) = -s * b.x - c * b.y;
  ja(1, 2) = c * b.x - s * b.y;
  return ja * cov_a * ja.transpose() + rotateCovariance(cov_b, a.phi);  // b's Jacobian: a's rotation
}

Eigen::Matrix3d rotateCovariance(const Eigen::Matrix3d& cov, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  r(0, 0) = c, r(0, 1) = -s, r(1, 0) = s, r(1, 1) = c;
  return r * cov * r.transpose();
}

}  // namespace radarslam
