#pragma once
// Local bundle adjustment (paper Sec. III-B): the poses of a window of keyframes and the map
// points they observe are refined together by weighted least squares with Levenberg-Marquardt
// (Ceres), minimising for every observation z_kj (map point j seen by keyframe k, in k's sensor
// frame) the robust (Huber) cost of
//     r_kj = (R(phi_k)^T (p_j - t_k) - z_kj) / sigma,
// plus relative-pose priors between consecutive keyframes of the window (the tracked odometry).
// Keyframes outside the window that observe the same points are held fixed (gauge freedom).
#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace radarslam {

struct LocalMappingParams;

struct BAObservation {
  std::size_t keyframe = 0;  ///< index into BAProblem::poses
  std::size_t point = 0;     ///< index into BAProblem::points
  Eigen::Vector2d z;         ///< sensor frame
  /// The shape of z's information (frontend/structure_information.h): the residual is weighed by it
  /// (point to line on walls); identity = isotropic.
  Eigen::Matrix2d information = Eigen::Matrix2d::Identity();
};

struct BAPrior {
  std::size_t from = 0, to = 0;  ///< indices into poses
  mrpt::math::TPose2D relative;  ///< measured pose of `to` in the frame of `from`
};

struct BAProblem {
  std::vector<mrpt::math::TPose2D> poses;  ///< map frame; optimised in place
  std::vector<bool> fixed;                 ///< per pose
  std::vector<Eigen::Vector2d> points;     ///< map frame; optimised in place
  std::vector<BAObservation> observations;
  std::vector<BAPrior> priors;
};

struct BAReport {
  double initial_cost = 0, final_cost = 0;
  int iterations = 0;
  bool converged = false;
  std::size_t outliers = 0;  ///< observations beyond the Huber width after the solve
};

/// Solves `problem` in place. Needs at least one fixed pose; with none, the first pose is fixed.
BAReport solveLocalBundleAdjustment(BAProblem& problem, const LocalMappingParams& params);

}  // namespace radarslam
