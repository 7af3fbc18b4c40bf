#pragma once
// First-order covariance propagation on SE(2), shared by the localiser's integrity checks
// (reloc/integrity.h) and keyframe culling (map/keyframe_culling.h).
#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

namespace radarslam {

/// a (+) b with the first-order covariance (a's in the map frame, b's in a's frame).
Eigen::Matrix3d composeCovariance(const mrpt::math::TPose2D& a, const Eigen::Matrix3d& cov_a,
                                  const mrpt::math::TPose2D& b, const Eigen::Matrix3d& cov_b);

/// The covariance of an (x, y, phi) error expressed in a frame rotated by `angle`: R cov R^T with
/// R rotating the (x, y) block (e.g. a covariance in the query's frame moved into the map's).
Eigen::Matrix3d rotateCovariance(const Eigen::Matrix3d& cov, double angle);

}  // namespace radarslam
