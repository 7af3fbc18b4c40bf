#include "radarslam/frontend/motion_prior_bound.h"

#include <algorithm>
#include <cmath>

namespace radarslam {

MotionPriorBound::MotionPriorBound(const MatchParams& params, double keypoint_sigma_m, double max_radius_m)
    : params_(params), keypoint_sigma_m_(keypoint_sigma_m), max_radius_m_(max_radius_m) {}

void MotionPriorBound::addDeviation(const mrpt::math::TPose2D& predicted,
                                    const mrpt::math::TPose2D& estimated) {
  const mrpt::math::TPose2D d = estimated - predicted;  // T_pred^-1 (+) T_est
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.phi)) return;
  sum_t2_ += d.x * d.x + d.y * d.y;
  const double phi = std::remainder(d.phi, 2.0 * M_PI);
  sum_phi2_ += phi * phi;
  const Eigen::Vector3d v(d.x, d.y, phi);
  sum_dd_ += v * v.transpose();
  ++n_;
}

Eigen::Matrix3d MotionPriorBound::covariance() const {
  if (n_ < params_.adaptive_min_samples) return Eigen::Matrix3d::Zero();
  return sum_dd_ / static_cast<double>(n_);
}

double MotionPriorBound::sigmaTranslation() const { return n_ > 0 ? std::sqrt(sum_t2_ / n_) : 0.0; }
double MotionPriorBound::sigmaRotation() const { return n_ > 0 ? std::sqrt(sum_phi2_ / n_) : 0.0; }

SearchRadius MotionPriorBound::radius(int stale_frames) const {
  const double growth = std::sqrt(1.0 + std::max(0, stale_frames));  // a velocity random walk
  if (!params_.adaptive_radius || n_ < params_.adaptive_min_samples) {
    const double r = std::min(max_radius_m_, params_.radius_m * growth);
    return {r, 0.0, r};
  }
  const double k = params_.radius_sigmas;
  const double st2 = sum_t2_ / n_, sphi = std::sqrt(sum_phi2_ / n_);
  SearchRadius r;
  r.fixed_m = k * std::sqrt(growth * growth * st2 + 2.0 * keypoint_sigma_m_ * keypoint_sigma_m_);
  r.per_range = k * growth * sphi;
  r.max_m = max_radius_m_;
  return r;
}

}  // namespace radarslam
