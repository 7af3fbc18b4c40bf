#pragma once
// The shape of a keypoint's position information from its image neighbourhood (ours, issue 13):
// the structure tensor S = sum over the patch of grad I grad I^T, whose inverse is the shape of the
// Lucas-Kanade / Foerstner covariance of the patch's position. On an extended structure (a wall, a
// kerb, the concentric walls of a turning circle) S is thin: the position is known across the
// structure, not along it. A keypoint there is placed along it by how the scene looks from the
// sensor (the bright spot of a smooth wall faces the sensor), so it moves with the sensor, and
// matching it point to point pulls the pose estimate of eq. (4) toward no motion along the
// structure. Weighting its residual by S (point to line) removes that pull.
//
// One exception: a compact target blurred by the beam's width is elongated along the beam's arc
// (its normal is radial) although its centre is well placed; an elongation within
// `beam_blur_tolerance_deg` of the arc keeps the isotropic weight.
#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace radarslam {

struct StructureInformationParams {
  /// weigh each match by its reference point's image structure (point to line on walls and kerbs); false:
  /// every match weighs its residual isotropically
  bool enabled = true;
  /// an elongation within this angle of the beam's arc is the beam's blur (isotropic weight); valid [0, 90]
  double beam_blur_tolerance_deg = 30.0;
};

/// The information shape (largest eigenvalue 1) of the keypoint at `pixel` of `smooth` (CV_32F),
/// from the gradients within `radius_px` of it, in metres coordinates: `pixel_to_metres` is the
/// image's linear map from pixel offsets to metre offsets, `position_m` the keypoint in metres
/// (sensor at the origin). Identity when the patch leaves the image, has no gradient, or is
/// elongated along the beam's arc.
Eigen::Matrix2d structureInformation(const cv::Mat& smooth, cv::Point2f pixel, int radius_px,
                                     const Eigen::Matrix2d& pixel_to_metres,
                                     const Eigen::Vector2d& position_m,
                                     const StructureInformationParams& params = {});

}  // namespace radarslam
