#pragma once
// The information (inverse covariance) of a 2-D point-cloud alignment, estimated from the
// alignment itself, so that a loop along a featureless wall says "I know the distance to the wall,
// not where along it I am" (issue 13, item 6: loop information from estimated uncertainty).
//
// For each inlier (query point q moved by the pose onto its nearest candidate point c):
//  - the candidate's local structure is the PCA of its neighbours within normal_radius_m. A linear
//    neighbourhood (eigenvalue ratio >= linearity_ratio) constrains only its normal n: the
//    residual is point-to-line, J = n^T [I | (R q)^perp] (Censi, ICRA 2007; the Hessian of the
//    point-to-plane cost). Anything else (a pole, a corner, a lone peak) constrains both axes:
//    J = [I | (R q)^perp], point-to-point.
//  - sigma^2 is the mean squared residual along the constrained directions (floored at
//    min_sigma_m: range quantisation and peak jitter never vanish).
//  - neighbouring radar peaks are not independent measurements (one wall gives dozens): each
//    cell of correlation_length_m holds one measurement's worth of information, shared by the
//    inliers that fall into it.
// information = sum_i w_i J_i^T J_i / sigma^2, w_i = 1 / (inliers in q_i's cell).
#include <Eigen/Core>

#include <span>

#include "radarslam/loop/point_index_2d.h"

namespace radarslam {

struct AlignmentInformationParams {
  double normal_radius_m = 1.5;       ///< neighbourhood of a candidate point for its normal; valid (0, 100]
  double linearity_ratio = 4.0;       ///< largest / smallest PCA eigenvalue for a line; valid [1, 1e6]
  double correlation_length_m = 1.0;  ///< one measurement per cell of this size; valid (0, 100]
  double min_sigma_m = 0.05;          ///< floor of the residual sigma; valid [0, 100]
};

/// `aligned_query`: query points already moved by the pose (x, y, th); `centre`: the pose's
/// translation (the rotation centre of the derivative). `candidate` indexes the candidate cloud.
/// Only pairs closer than `inlier_distance_m` count. Returns zero if there are none.
Eigen::Matrix3d alignmentInformation(std::span<const Eigen::Vector2d> aligned_query,
                                     const Eigen::Vector2d& centre, const PointIndex2D& candidate,
                                     double inlier_distance_m, const AlignmentInformationParams& params = {});

}  // namespace radarslam
