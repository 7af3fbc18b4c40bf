#pragma once
// M2DP global place descriptor (He, Wang, Zhang, IROS 2016), used by RadarSLAM on the peak cloud
// of Algorithm 1 for loop-closure candidate retrieval (paper Sec. III-C).
//
// Defining structure, as in the M2DP paper: centre the cloud at its centroid, rotate it into its
// PCA frame, project it onto p x q planes (normal azimuth theta in [0, pi), elevation phi in
// [0, pi/2)), count points per bin of l concentric rings (radii r, 4r, ..., l^2 r) x t sectors on
// each plane (sector 0 along the projected first PCA axis), stack the p*q signatures as the rows
// of A (pq x lt), and take [u1; v1], the first left and right singular vectors of A.
//
// Adaptation to a planar radar cloud (see docs/loop_closure.md):
//  - The third coordinate is the point's return power, standardised over the cloud and scaled to
//    metres (z = power_height_m * (power - mean) / std). Planes with a high elevation see the
//    2D layout, planes with a low elevation see a "side view" of where strong returns are.
//    power_height_m = 0 gives a purely geometric descriptor (the planes then foreshorten the
//    2D layout along one direction).
//  - PCA runs on x, y only (z is not a direction in space); e2 = e1 rotated by +90 degrees, so the
//    frame is right-handed and a rotated cloud gets the same frame. The sign of e1 is chosen so
//    that the third moment of the points along e1 is positive (deterministic); when that moment
//    is close to zero the sign is unreliable, so the descriptor with the other sign can be
//    computed too (flip_first_axis) and queried as well.
//  - The SVD sign ambiguity (u1, v1) ~ (-u1, -v1) is fixed by making sum(v1) >= 0 (A is
//    non-negative, so v1 is single-signed up to noise).
//  - Bin counts are divided by the number of points (density robustness); the outer ring radius
//    is a quantile of the point distances from the centroid (robust to a few far outliers);
//    points beyond it count in the outermost ring.
#include <Eigen/Core>
#include <span>

#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

class YamlParams;

struct M2DPParams {
  int azimuths = 4;               ///< p; valid [1, 64]
  int elevations = 16;            ///< q; valid [1, 64]
  int rings = 8;                  ///< l; valid [1, 64]
  int sectors = 16;               ///< t; valid [1, 64]
  double power_height_m = 5.0;    ///< scale of the power coordinate (0 = planar cloud); valid [0, 1000]
  double radius_quantile = 0.95;  ///< outer ring radius = this quantile of point distances; valid (0, 1]
  std::size_t min_points = 10;    ///< fewer points: descriptor is invalid (empty); valid [3, 100000]
};

/// Overrides `params` from the keys azimuths, elevations, rings, sectors, power_height_m,
/// radius_quantile, min_points of `yaml`.
void loadParams(const YamlParams& yaml, M2DPParams& params);

/// The descriptor [u1; v1] (length p*q + l*t, unit-norm halves), or an empty vector when the
/// cloud has fewer than min_points points or a degenerate layout.
using M2DPDescriptor = Eigen::VectorXf;

/// `flip_first_axis` = true computes the descriptor with the other sign of the first PCA axis
/// (the cloud rotated by 180 degrees in its PCA frame).
M2DPDescriptor computeM2DP(std::span<const RadarPoint> cloud, const M2DPParams& params = {},
                           bool flip_first_axis = false);

/// Euclidean distance between two descriptors (0..2*sqrt(2)); +inf if either is empty or the
/// sizes differ.
float m2dpDistance(const M2DPDescriptor& a, const M2DPDescriptor& b);

}  // namespace radarslam
