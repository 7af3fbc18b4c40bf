#pragma once
// Absolute trajectory error (ATE, after a rigid SE(2) alignment) and relative pose error (RPE,
// frame to frame), on poses matched frame by frame.
#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <vector>

namespace radarslam::eval {

/// Summary of a list of non-negative errors. All NaN when empty.
struct ErrorStats {
  std::size_t count = 0;
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;
};
ErrorStats computeStats(std::vector<double> values);

struct AteResult {
  mrpt::math::TPose2D alignment;                 ///< T with T (+) est ~ gt (see alignSE2)
  ErrorStats trans_m;                            ///< |aligned est position - gt position|
  ErrorStats rot_deg;                            ///< |yaw(aligned est) - yaw(gt)|
  std::vector<mrpt::math::TPose2D> est_aligned;  ///< T (+) est_i, for plots
};
/// Aligns est's positions onto gt's (alignSE2) and measures the residuals.
AteResult computeAte(const std::vector<mrpt::math::TPose2D>& gt, const std::vector<mrpt::math::TPose2D>& est);

struct RpeResult {
  ErrorStats trans_m;  ///< |trans(E_i)|, E_i = inv(dGT_i) dEst_i between frames i, i+1
  ErrorStats rot_deg;  ///< |angle(E_i)|
  std::vector<double> per_frame_trans_m;
  std::vector<double> per_frame_rot_deg;
};
RpeResult computeRpe(const std::vector<mrpt::math::TPose2D>& gt, const std::vector<mrpt::math::TPose2D>& est);

}  // namespace radarslam::eval
