#pragma once
// How far the motion prior may be off: the search radius of the motion-prior matching (paper
// Sec. III-A, first mechanism) from the running RMS of the constant-velocity model's error (ours,
// after KISS-ICP's adaptive threshold, Vizzo et al. RA-L 2023, Sec. III-C).
//
// Each tracked frame contributes its model deviation, the prediction's error against the final
// estimate, D = T_pred^-1 (+) T_est: sigma_t^2 = mean |D_xy|^2 and sigma_phi^2 = mean D_phi^2. A
// current point p at range rho then differs from its prediction by the translation error, the
// heading error swept over rho, and both frames' keypoint jitter sigma_kp:
//   sigma(rho)^2 = sigma_t^2 + (rho sigma_phi)^2 + 2 sigma_kp^2,   radius(rho) = k sigma(rho).
// A fixed radius is either too small for far points in a turn (a 2 deg heading error is 3 m at
// 87 m) or large enough near the sensor to accept vehicle-fixed structure (sidelobe fans, the
// azimuth-sampling pattern along a wall), which matches at zero motion and stops the estimate.
// After n frames without a good estimate the velocity is n frames stale: the variance grows with
// (1 + n) (a velocity random walk).
#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>

#include "radarslam/frontend/radius_matcher.h"

namespace radarslam {

class MotionPriorBound {
 public:
  /// keypoint_sigma_m: one frame's keypoint position noise; max_radius_m caps every radius.
  MotionPriorBound(const MatchParams& params, double keypoint_sigma_m, double max_radius_m);

  /// One tracked frame: the constant-velocity prediction and the final estimate (both T_prev_cur).
  void addDeviation(const mrpt::math::TPose2D& predicted, const mrpt::math::TPose2D& estimated);

  /// The radius for the next frame, `stale_frames` frames after the last good estimate. Until
  /// adaptive_min_samples deviations are known (or when adaptive_radius is off): radius_m,
  /// growing the same way with staleness.
  SearchRadius radius(int stale_frames = 0) const;

  int samples() const { return n_; }
  double sigmaTranslation() const;  ///< m
  double sigmaRotation() const;     ///< rad
  /// Second moment of D (x, y in the prediction's frame, phi), i.e. the prediction error's
  /// covariance about zero: the motion model's prior on the next estimate (pose_refiner.h). Zero
  /// until adaptive_min_samples deviations are known.
  Eigen::Matrix3d covariance() const;

 private:
  MatchParams params_;
  double keypoint_sigma_m_;
  double max_radius_m_;
  int n_ = 0;
  double sum_t2_ = 0.0, sum_phi2_ = 0.0;
  Eigen::Matrix3d sum_dd_ = Eigen::Matrix3d::Zero();
};

}  // namespace radarslam
