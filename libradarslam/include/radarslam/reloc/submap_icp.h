#pragma once
// Scan-to-map registration for map-based localisation: a local submap (the peak clouds of the map
// keyframes near a predicted pose, in the map frame, thinned on a voxel grid, in a kd-tree) and a
// robust ICP of a scan's peak cloud against it.
//
// ICP (Gauss-Newton on SE(2), Cauchy-weighted): each scan point is matched to its nearest submap
// point within a gate that shrinks from max_correspondence_m to inlier_distance_m over the
// iterations. Where the submap is locally linear (a wall: PCA of the neighbours within
// normal_radius_m, smallest/largest eigenvalue <= max_planarity) the residual is point-to-line
// (along the wall's normal), elsewhere point-to-point.
// Covariance = sigma^2 H^-1 (pseudo-inverse with eigenvalues clamped at 1e-6; H = Gauss-Newton Hessian J^T W
// J of the final inliers, sigma^2 = their weighted residual variance, at least min_sigma_m^2) times
// covariance_scale (> 1 because neighbouring radar points are not independent measurements), plus
// a heading model-error variance heading_sigma_floor_deg^2 and a position one position_sigma_floor_m^2
// (the slam_map_ pair for maps of motion-compensated clouds, chosen by the map tracker).
#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "radarslam/map/keyframe_map.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

class YamlParams;

struct SubmapParams {
  double radius_m = 60;  ///< keyframes within this distance of the centre; valid (0, 10000]
  double voxel_m = 0.5;  ///< submap thinning (centroid per voxel); valid [0.01, 100]
  double max_point_range_m =
      0;  ///< keyframe points farther from their sensor are dropped (0 = all); valid [0, 10000]
  double rebuild_distance_m =
      15;  ///< a tracker rebuilds when the prediction moves this far; valid [0, 10000]
  /// A tracker uses only keyframes within this path distance (through the map's odometry and loop
  /// edges, reloc/map_connectivity.h) of the keyframe it is tracking: one copy of a street the map
  /// holds twice; keyframes nearby but farther along the graph are a second copy, registered only
  /// to report the ambiguity. 0 = every keyframe within radius_m (no copies told apart).
  /// valid [0, 1000000]
  double max_path_m = 400;
};

struct IcpParams {
  int max_iterations = 30;            ///< valid [1, 1000]
  double max_correspondence_m = 3.0;  ///< gate of the first iteration; valid (0, 1000]
  double inlier_distance_m = 1.0;     ///< gate of the last iterations and inlier definition; valid (0, 1000]
  double cauchy_m = 0.5;              ///< robust kernel scale; valid (0, 100]
  double normal_radius_m = 1.5;       ///< neighbourhood for the local line fit; valid (0, 100]
  double max_planarity = 0.1;         ///< eigenvalue ratio below which a point is on a line; valid [0, 1]
  double convergence_m = 1e-3,
         convergence_rad = 1e-4;       ///< valid convergence_m [0, 10], convergence_rad [0, 1]
  double scan_voxel_m = 1.0;           ///< query cloud thinning (strongest point per voxel); valid [0, 100]
  std::size_t max_scan_points = 1000;  ///< after thinning (even stride); valid [10, 1000000]
  double min_sigma_m = 0.05;           ///< valid [0, 100]
  double covariance_scale =
      50.0;  ///< calibrated on the simulator demo (docs/localization.md); valid (0, 1000000]
  /// Heading model error added to the covariance (1 sigma): the scan-to-map heading error is
  /// systematic (lag-1 autocorrelation 0.85), not the independent point noise sigma^2 H^-1 models;
  /// chosen on train sequences (docs/localization.md, "Calibrated covariance"); valid [0, 90]
  double heading_sigma_floor_deg = 0.25;
  double position_sigma_floor_m = 0.0;  ///< position model error (1 sigma, per axis); valid [0, 100]
  /// The model errors for a map of motion-compensated keyframe clouds (`radarslam map`; the two above
  /// are for maps of raw sweeps, map-synth): the SLAM keyframe poses carry the map's own local error,
  /// so the position gets a floor, and the heading error is smaller. Chosen on the train sequence
  /// grid-s1-clear as sqrt(mean(e^2 - sigma_icp^2)) (docs/localization.md); valid [0, 90] / [0, 100]
  double slam_map_heading_sigma_floor_deg = 0.14;  ///< heading model error, maps of compensated clouds
  double slam_map_position_sigma_floor_m = 0.035;  ///< position model error, maps of compensated clouds
  /// The fit profile along the weakest position direction: the fit score and the robust cost are
  /// also evaluated with the solution shifted by +-profile_shift_m along the largest-variance xy
  /// eigenvector (IcpResult::profile_fit, profile_chi2). A cost that stays flat there (a featureless
  /// wall) is a direction the curvature sigma^2 H^-1 cannot be trusted in, whatever its size.
  /// Evaluated when the caller asks for it (LocalSubmap::registerScan, MapTracker's check (g));
  /// 0 = never; valid [0, 100]
  double profile_shift_m = 2.0;
};

void loadParams(const YamlParams& yaml, SubmapParams& params);
void loadParams(const YamlParams& yaml, IcpParams& params);

struct IcpResult {
  mrpt::math::TPose2D pose;                                  ///< scan sensor pose in the map frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  ///< of (x, y, phi)
  double fit_score = 0;                                      ///< inliers / scan points used
  std::size_t inliers = 0;
  std::size_t scan_points = 0;
  double rms_m = 0;  ///< inlier residual RMS
  /// The robust cost at the solution: the Cauchy loss rho(r) = cauchy_m^2 / 2 log(1 + r^2 /
  /// cauchy_m^2) of each inlier's residual, rho(inlier_distance_m) for each scan point beyond the
  /// gate. Near the minimum cost - cost_min = d^T H d / 2, so two registrations of one scan compare
  /// as a likelihood ratio: 2 (cost_b - cost_a) / (covariance_scale sigma2) (MapTracker, check (h)).
  double cost = 0;
  double sigma2 = 0;  ///< the residual variance of sigma^2 H^-1 (before covariance_scale and the floors)
  /// The better fit score of the solution shifted by +-IcpParams::profile_shift_m along
  /// weak_direction (0 when not evaluated).
  double profile_fit = 0;
  /// The smaller likelihood ratio of those two shifted solutions to this one, 2 (cost_shifted -
  /// cost) / (covariance_scale sigma2) (infinite when not evaluated): within a chi^2 bound the scan
  /// cannot tell the shifted position from its own.
  double profile_chi2 = std::numeric_limits<double>::infinity();
  Eigen::Vector2d weak_direction = Eigen::Vector2d::UnitX();  ///< largest-variance xy direction (unit)
  int iterations = 0;
  bool converged = false;
};

/// A keyframe's stored cloud (sensor frame) as a scan's peak cloud: what the registration and the
/// global descriptors take (range from the position; no azimuth).
std::vector<RadarPoint> toRadarPoints(const std::vector<KeyframePoint>& pts);

/// The thinned map-frame points of the keyframes near a centre, with a kd-tree.
class LocalSubmap {
 public:
  LocalSubmap();
  ~LocalSubmap();
  LocalSubmap(LocalSubmap&&) noexcept;
  LocalSubmap& operator=(LocalSubmap&&) noexcept;

  /// Keyframes of `map` within params.radius_m of (cx, cy); with `allowed`, only those whose
  /// entry (by position in map.keyframes) is non-zero.
  static LocalSubmap build(const KeyframeMap& map, double cx, double cy, const SubmapParams& params,
                           const std::vector<char>* allowed = nullptr);
  /// Every keyframe's points (tests, small maps).
  static LocalSubmap fromPoints(std::vector<Eigen::Vector2d> map_points, double voxel_m);

  std::size_t size() const;
  std::size_t keyframes() const { return keyframe_indices_.size(); }
  /// Positions in map.keyframes of the keyframes it holds (ascending).
  const std::vector<std::size_t>& keyframeIndices() const { return keyframe_indices_; }
  double centreX() const { return cx_; }
  double centreY() const { return cy_; }

  /// A scan's peak cloud (sensor frame) as registration uses it: the strongest point per
  /// params.scan_voxel_m voxel, then an even stride down to params.max_scan_points.
  static std::vector<Eigen::Vector2d> thinScan(std::span<const RadarPoint> scan, const IcpParams& params);

  /// Registers `scan` (sensor frame) starting from `initial` (sensor pose in the map frame); with
  /// `fit_profile`, also the fit profile (IcpResult::profile_fit, when params.profile_shift_m > 0).
  IcpResult registerScan(std::span<const RadarPoint> scan, const mrpt::math::TPose2D& initial,
                         const IcpParams& params, bool fit_profile = false) const;
  /// The same for a scan already thinned by thinScan (several starts register it once thinned).
  IcpResult registerThinned(const std::vector<Eigen::Vector2d>& thinned, const mrpt::math::TPose2D& initial,
                            const IcpParams& params) const;
  /// Fills result.profile_fit, profile_chi2 and weak_direction for the registration `result` of
  /// `thinned` (nothing when params.profile_shift_m is 0 or it has fewer than 3 inliers).
  void fitProfile(const std::vector<Eigen::Vector2d>& thinned, const IcpParams& params,
                  IcpResult& result) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::size_t> keyframe_indices_;
  double cx_ = 0, cy_ = 0;
};

}  // namespace radarslam
