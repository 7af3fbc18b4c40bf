#pragma once
// Which rigid motion is the vehicle's? (ours, an extension of paper Sec. III-A.) The maximum clique
// of the consistency graph is the largest set of matches one rigid motion explains; it is the static
// world when most matched structure is static. Beside a featureless wall the static matches are few
// and a vehicle in the next lane is a rigid set of its own that can be the larger one; taking its
// motion slides the odometry along the wall (docs/odometry.md). So the maximum clique of the
// remaining matches (the second rigid motion) is weighed against the first by the likelihood of
// each explanation:
//   log L(h) = n_h ln(R^2 / (4 sigma_k^2))                 each match explained: the density of a
//                                                           static match's residual N(0, 2 sigma_k^2 I)
//                                                           against a match anywhere in the search disc
//            - |d_h|^2 / (2 s_h^2) - ln(2 pi s_h^2)       the motion's deviation d_h from the
//                                                           constant-velocity prediction, with
//   s_h^2 = sigma_t^2 + 2 sigma_k^2 / n_h                   the prediction's running error (the adaptive
//                                                           radius's sigma_t) plus the SVD pose's noise.
// No constant is fitted: R is the radius the matches were searched in, sigma_k the keypoint noise
// and sigma_t the running RMS the search radius already uses.
#include <mrpt/math/TPose2D.h>

#include <vector>

#include "radarslam/frontend/correspondence.h"
#include "radarslam/frontend/max_clique.h"

namespace radarslam {

/// The constant-velocity prediction a scan's motion is weighed against.
struct MotionPrediction {
  mrpt::math::TPose2D predicted;  ///< T_k_t predicted from the last velocity
  double sigma_m = 0.0;           ///< running RMS of the prediction's translation error (> 0)
  double search_radius_m = 0.0;   ///< radius the matches were searched in (> 0)
  double keypoint_sigma_m = 0.0;  ///< one keypoint's position noise (> 0)
};

/// log L(h) above for a rigid set of n matches whose SVD pose is `pose`.
double rigidMotionLogLikelihood(const mrpt::math::TPose2D& pose, std::size_t n,
                                const MotionPrediction& prediction);

struct RigidMotionChoice {
  std::vector<int> vertices;  ///< the chosen rigid set (indices into the matches), sorted
  bool second = false;        ///< the second rigid motion was more likely than the maximum clique
};

/// Between the maximum clique `first` of `graph` and the maximum clique of the matches outside it
/// (computed here with the same step budget; considered only if it has >= min_inliers matches),
/// the one whose explanation is more likely. Returns `first` unchanged when no second rigid set of
/// that size exists or either SVD pose fails.
RigidMotionChoice chooseRigidMotion(const Correspondences& matches, const DenseGraph& graph,
                                    const std::vector<int>& first, const MotionPrediction& prediction,
                                    int min_inliers, long max_clique_steps);

}  // namespace radarslam
