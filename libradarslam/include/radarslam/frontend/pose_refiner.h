#pragma once
// Pose refinement against the keyframe's map points (paper Sec. III-A, eq. (4)):
//   T* = argmin_T sum_i rho( |P_ref^i - T (+) P_cur^i| )
// solved by iteratively re-weighted Gauss-Newton on (x, y, yaw) with a Huber kernel rho (the
// paper's plain L2 sum is the limit of a large Huber threshold). Each residual may carry its own
// information shape (frontend/structure_information.h: point to line on extended structures).
#include <mrpt/math/TPose2D.h>

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
};

struct RefineResult {
  mrpt::math::TPose2D pose;
  double rms_m = 0.0;  ///< weighted RMS residual at the solution
  int iterations = 0;
};

/// `shapes`, when not empty, holds one information shape per match (of its reference point), used
/// instead of the azimuth model above.
RefineResult refinePose(const Correspondences& matches, const mrpt::math::TPose2D& initial,
                        const RefineParams& params = {}, std::span<const Eigen::Matrix2d> shapes = {});

}  // namespace radarslam
