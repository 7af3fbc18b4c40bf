#pragma once
// Descriptor matching restricted by a motion prior (paper Sec. III-A, first mechanism): a
// current keypoint is only compared with keyframe keypoints within `radius_m` of where the
// predicted motion puts it, instead of exhaustively.
#include <mrpt/math/TPose2D.h>

#include <opencv2/core/mat.hpp>

#include <Eigen/Core>

#include <vector>

#include "radarslam/frontend/correspondence.h"

namespace radarslam {

struct MatchParams {
  double radius_m = 4.0;        ///< search radius around the prediction while tracking; valid (0, 1000]
  double init_radius_m = 12.5;  ///< on initialisation / after a tracking loss (paper: 50 px); valid (0, 1000]
  double ratio = 0.9;           ///< Lowe ratio, best / second best within the radius (1 = off); valid (0, 1]
  int max_descriptor_distance =
      80;              ///< Hamming bits (binary descriptors); ignored for float ones; valid [0, 1024]
  bool mutual = true;  ///< keep only mutual best matches
};

struct FeatureSet {
  std::vector<Eigen::Vector2d> xy;  ///< metres, in the frame's own sensor frame
  cv::Mat descriptors;              ///< one row per point
  int norm_type = 0;
};

/// Matches `cur` against `ref` with prior T_ref_cur. Correspondence::cur/ref hold the points.
Correspondences matchWithinRadius(const FeatureSet& cur, const FeatureSet& ref,
                                  const mrpt::math::TPose2D& prior, double radius_m,
                                  const MatchParams& params);

}  // namespace radarslam
