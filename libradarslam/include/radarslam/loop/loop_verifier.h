#pragma once
// Geometric verification of a loop candidate (paper Sec. III-C): the relative pose between the
// query's and the candidate keyframe's peak clouds with no initial guess (a revisit may be in the
// opposite direction), then acceptance tests that keep false loops out.
//
//  1. Global search (consensus over hypotheses, deterministic): both clouds are thinned on a
//     voxel grid; for each of `rotation_steps` rotations every (query, candidate) point pair votes
//     for the translation that would overlay them (a 2D Hough grid); each rotation's strongest
//     translation cell is a hypothesis. Hypotheses are taken by votes with non-maximum
//     suppression, the best `hypotheses` are refined by a short point-to-point ICP on the thinned
//     clouds and scored by their inlier count (RANSAC-style consensus).
//  2. Uniqueness (ambiguous places, e.g. a street of identical facades): the best hypothesis must
//     beat every hypothesis that is far from it in pose by a margin (second / best <=
//     max_ambiguity_ratio); otherwise the place is ambiguous and the loop is rejected. When every
//     rival is the best alignment slid along one line at the same heading (a straight featureless
//     wall; not a street that also fits turned by 180 degrees), the result says so (`slide`): the place is
//     then known across that line and in heading, unknown along it, which a caller may use as a partial loop.
//  3. Refinement: mrpt::slam::CICP (classic ICP) on the full clouds from the best hypothesis.
//  4. Acceptance: enough inliers (absolute and as a share of the smaller cloud), a small inlier
//     RMS, and inliers spread around the sensor (at least min_inlier_sectors of 8 bearing sectors).
//
// The information matrix is estimated from the final alignment (loop/alignment_information.h):
// point-to-line where the candidate is locally a line, point-to-point elsewhere, one measurement
// per correlation cell, sigma from the residuals. Along a featureless wall it is weak along the wall.
#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

#include "radarslam/loop/alignment_information.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

class YamlParams;

struct LoopVerifierParams {
  double voxel_m = 1.0;                 ///< thinning for the global search; valid [0, 100]
  std::size_t max_search_points = 300;  ///< per cloud, after thinning; valid [3, 100000]
  int rotation_steps = 180;             ///< 2 degrees; valid [4, 3600]
  double max_translation_m = 40;        ///< search window for the translation; valid (0, 1000]
  double vote_cell_m = 1.0;             ///< Hough grid cell; valid [0.01, 100]
  int hypotheses = 8;                   ///< refined and scored; valid [1, 1000]
  double suppression_distance_m = 3.0;  ///< hypotheses closer than this (and angle) are one; valid [0, 1000]
  double suppression_angle_deg = 15.0;  ///< valid [0, 180]
  double inlier_distance_m = 1.0;       ///< point-to-point inlier gate after alignment; valid (0, 100]
  double max_ambiguity_ratio = 0.7;     ///< second-best (far in pose) / best consensus; valid [0, 10]
  std::size_t min_inliers = 40;         ///< on the full clouds; valid [0, 1e6]
  double min_inlier_ratio = 0.4;        ///< inliers / size of the smaller full cloud; valid [0, 1]
  double max_rms_m = 0.6;               ///< inlier RMS after ICP; valid (0, 100]
  int min_inlier_sectors = 4;           ///< of 8 bearing sectors around the query sensor; valid [0, 8]
  /// keys normal_radius_m, linearity_ratio, correlation_length_m, min_sigma_m
  AlignmentInformationParams information;
  /// Not a YAML key: the caller says whether it uses LoopVerification::information (a radius
  /// search and a 2x2 PCA per aligned point); false leaves it zero.
  bool estimate_information = true;
};

/// Overrides `params` from the YAML keys of the same names.
void loadParams(const YamlParams& yaml, LoopVerifierParams& params);

struct LoopVerification {
  bool accepted = false;
  std::string reason;                 ///< why it was rejected (empty when accepted)
  mrpt::math::TPose2D relative_pose;  ///< query keyframe in the candidate keyframe's frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  ///< of relative_pose (x, y, phi)
  double inlier_ratio = 0;                                ///< the fit score
  std::size_t inliers = 0;
  double rms_m = 0;
  double ambiguity_ratio = 1;  ///< second-best / best consensus (lower = more unique)
  /// The hypotheses far from the best (beyond the suppression distance or angle) scoring more than
  /// max_ambiguity_ratio of it, each as the pose offset best^-1 (+) rival (in the query's frame at the
  /// best alignment): where else the query fits almost as well. Empty when the place is unique.
  std::vector<mrpt::math::TPose2D> rivals;
  /// Refused as ambiguous only: the best alignment passed every other acceptance test (global
  /// localisation can follow the rivals over the next scans, reloc/fix_hypotheses.h).
  bool ambiguous_only = false;
  /// The rivals are all slides of the best alignment along one line: each within one search
  /// rotation step (360 / rotation_steps degrees) of its heading and within inlier_distance_m of
  /// that line (across it they agree as closely as the inlier gate can tell).
  bool slide = false;
  /// When `slide`: the line's unit direction, in the same frame as the rivals' offsets (the query's
  /// frame, that of relative_pose's error), and the farthest rival along it.
  Eigen::Vector2d slide_direction = Eigen::Vector2d::Zero();
  double slide_extent_m = 0;
  int inlier_sectors = 0;
};

/// Verifies that `query` (a peak cloud in its sensor frame) was taken at the place of
/// `candidate`, and finds the relative pose.
LoopVerification verifyLoop(std::span<const RadarPoint> query, std::span<const RadarPoint> candidate,
                            const LoopVerifierParams& params = {});

}  // namespace radarslam
