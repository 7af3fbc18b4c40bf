#pragma once
// Pose refinement against the keyframe's map points (paper Sec. III-A, eq. (4)):
//   T* = argmin_T sum_i rho( |P_ref^i - T (+) P_cur^i| )
// solved by iteratively re-weighted Gauss-Newton on (x, y, yaw) with a Huber kernel rho (the
// paper's plain L2 sum is the limit of a large Huber threshold). Each residual may carry its own
// information shape (frontend/structure_information.h: point to line on extended structures).
//
// Optionally (ours) a Gaussian prior on T, the motion model's prediction with the covariance of its
// measured error (frontend/motion_prior_bound.h): the maximum a posteriori pose
//   T* = argmin_T sum_i rho(e_i) / sigma^2 + D^T Sigma_pred^-1 D,   D = T_pred^-1 (+) T,
// with sigma^2 the matches' own residual variance. Where the matches constrain the pose (any
// ordinary scan: hundreds of points, millimetres) the prior moves it little; along a direction
// they leave free (a straight wall, concentric arcs about their centre) the motion model decides
// instead of the noise. The prior is gated: it is applied only if the rise of the normalised cost
// it causes, d^T (Sigma_pred + Sigma_data)^-1 d for the innovation d, is within a chi^2(3) bound;
// otherwise the motion left the model (or the matches are wrong) and the data's estimate stands.
#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>

#include <span>

#include "radarslam/frontend/correspondence.h"
#include "radarslam/frontend/structure_information.h"

namespace radarslam {

struct RefineParams {
  int iterations = 10;   ///< valid [0, 1000]
  double huber_m = 0.5;  ///< residuals beyond this are down-weighted (metres); valid (0, 100]
  /// Anisotropic point noise (0 = isotropic): a radar return is precise in range and blurred
  /// along the beam's arc, sigma_t = range * azimuth_sigma_rad. Residuals are then weighted by
  /// the inverse of diag(range_sigma_m^2, sigma_t^2) in the beam's frame (at the ref point).
  double azimuth_sigma_rad = 0.0;  ///< valid [0, 1]
  double range_sigma_m = 0.1;      ///< valid [0, 10]
  /// The reference points' information shapes from their image structure (odometry only).
  StructureInformationParams structure;
  /// weigh the constant-velocity prediction as a gated prior on the refined pose (ours, odometry only,
  /// docs/odometry.md); false: the paper's refinement from the matches alone
  bool motion_prior = true;
  /// the prior's innovation gate, a chi^2(3) quantile (11.34: 99 %); valid (0, 1e6]
  double motion_prior_chi2 = 11.34;
};

/// A Gaussian prior on the refined pose: its mean and the covariance of D = mean^-1 (+) T, i.e. in
/// the mean's own frame (x, y in metres, phi in radians); must be positive definite.
struct PosePrior {
  mrpt::math::TPose2D mean;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

struct RefineResult {
  mrpt::math::TPose2D pose;
  double rms_m = 0.0;  ///< weighted RMS residual at the solution
  int iterations = 0;
  double prior_chi2 = -1.0;    ///< the prior's innovation chi^2 (-1: no prior weighed)
  bool prior_applied = false;  ///< the prior passed its gate and is in the pose
};

/// `shapes`, when not empty, holds one information shape per match (of its reference point), used
/// instead of the azimuth model above. `prior`, when given, is weighed as above (whatever
/// params.motion_prior says: the caller decides).
RefineResult refinePose(const Correspondences& matches, const mrpt::math::TPose2D& initial,
                        const RefineParams& params = {}, std::span<const Eigen::Matrix2d> shapes = {},
                        const PosePrior* prior = nullptr);

}  // namespace radarslam
