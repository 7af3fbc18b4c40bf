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
  double radius_m =
      4.0;  ///< search radius while tracking, until the adaptive bound has its statistics; valid (0, 1000]
  double init_radius_m = 12.5;  ///< on initialisation / after a tracking loss (paper: 50 px); valid (0, 1000]
  double ratio = 0.9;           ///< Lowe ratio, best / second best within the radius (1 = off); valid (0, 1]
  int max_descriptor_distance =
      80;              ///< Hamming bits (binary descriptors); ignored for float ones; valid [0, 1024]
  bool mutual = true;  ///< keep only mutual best matches
  // Adaptive radius (ours, after KISS-ICP's adaptive threshold): radius(range) = k sigma from the
  // running RMS of the constant-velocity prediction's error, translation and rotation apart, so
  // far points get the room a heading error needs and near points stay tight (see
  // frontend/motion_prior_bound.h).
  bool adaptive_radius =
      true;                    ///< radius from the prediction's running error; false = fixed radius_m (paper)
  double radius_sigmas = 3.0;  ///< k, the bound in standard deviations; valid (0, 100]
  double keypoint_sigma_px = 1.0;  ///< keypoint position noise per scan, Cartesian pixels; valid [0, 100]
  int adaptive_min_samples = 10;   ///< tracked scans before the statistics replace radius_m; valid [1, 1e6]
};

/// Search radius around a predicted point as a function of the point's range from the sensor:
/// min(max_m, sqrt(fixed_m^2 + (per_range * range)^2)). A fixed radius r is {r, 0, r}.
struct SearchRadius {
  double fixed_m = 4.0;
  double per_range = 0.0;  ///< metres of radius per metre of range (k sigma_heading)
  double max_m = 4.0;
  double at(double range_m) const;
  static SearchRadius fixed(double r) { return {r, 0.0, r}; }
};

struct FeatureSet {
  std::vector<Eigen::Vector2d> xy;  ///< metres, in the frame's own sensor frame
  cv::Mat descriptors;              ///< one row per point
  int norm_type = 0;
};

/// Matches `cur` against `ref` with prior T_ref_cur. Correspondence::cur/ref hold the points. A
/// current point at range rho (in its own frame) is compared with reference points within
/// radius.at(rho) of its prediction.
Correspondences matchWithinRadius(const FeatureSet& cur, const FeatureSet& ref,
                                  const mrpt::math::TPose2D& prior, const SearchRadius& radius,
                                  const MatchParams& params);
/// The same with one radius for every point.
Correspondences matchWithinRadius(const FeatureSet& cur, const FeatureSet& ref,
                                  const mrpt::math::TPose2D& prior, double radius_m,
                                  const MatchParams& params);

}  // namespace radarslam
