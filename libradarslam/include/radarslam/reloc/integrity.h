#pragma once
// Integrity monitoring of map-based localisation (issue #14): checks that do not trust the map
// matcher alone decide whether a registered pose is reported as `tracking`, `degraded` (a pose
// with an honestly inflated covariance) or dropped (`lost`, global localisation again).
//
//  (a) odometry agreement: the innovation between the registered pose and the prediction
//      (previous pose (+) radar-odometry motion) is chi^2-tested with the combined covariance of the
//      prediction (previous pose covariance and the odometry noise model below) and the
//      registration; threshold = the chi^2(3) quantile of `chi2_probability` (no tuned constant);
//  (b) fit score against its running statistics: fit < median - fit_drop_sigmas * robust sigma
//      (1.4826 MAD, at least min_fit_sigma) of the last fit_history accepted scans;
//  (c) degeneracy: the xy covariance of the registration has a weak direction (eigenvalue ratio >
//      max_condition, e.g. a corridor) -> the registration is fused with the prediction
//      (information filter: the odometry fills the weak direction), `degraded`;
//  (e) consistency with the previous poses: the map-relative motion over the last window_scans
//      accepted scans against the odometry over the same scans, chi^2-tested likewise (a slow walk
//      of the matcher that each single step hides);
//  (f) coverage: a pose more than max_keyframe_distance_m from every map keyframe is outside the
//      mapped path (the map's points were seen from elsewhere, and where the SLAM map has no
//      keyframe it says nothing about its own accuracy): `degraded`, with the odometry noise
//      model over the distance from the nearest keyframe added to its covariance. SLAM keyframes
//      lie <= 2 m apart along the driven path, so 10 m is two lane widths beyond any of them.
// A failed check: the pose is the odometry prediction, its covariance the prediction's (it grows
// with every scan), status `degraded`; past max_failures consecutive failures or 3 sigma position
// > max_position_3sigma_m: `lost`.
#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

#include <deque>
#include <vector>

#include "radarslam/core/se2_covariance.h"
#include "radarslam/map/keyframe_map.h"

namespace radarslam {

class YamlParams;

struct IntegrityParams {
  bool enabled = true;  ///< false: the tracker's own tests only (as before issue #14)
  /// Odometry noise per scan (1 sigma, independent per scan): position sigma = floor + per_m * d,
  /// heading sigma = floor + per_rad * |dphi| + per_m * d (d = distance travelled in the scan).
  /// Valid: >= 0 each; defaults cover the radar odometry's drift (~2 % / 0.1 deg per m, docs).
  double odom_sigma_per_m = 0.02;
  double odom_sigma_floor_m = 0.05;
  double odom_sigma_rad_per_rad = 0.05;
  double odom_sigma_rad_per_m = 0.002;
  double odom_sigma_floor_rad = 0.005;
  double chi2_probability = 0.999;     ///< (0.5, 1): chi^2(3) quantile of the innovation tests
  int window_scans = 10;               ///< >= 2: window of check (e); 0 disables it
  int fit_history = 30;                ///< >= 5: accepted fit scores kept for check (b)
  double fit_drop_sigmas = 4.0;        ///< > 0: robust sigmas below the median that fail check (b)
  double min_fit_sigma = 0.03;         ///< > 0: floor of the robust fit sigma
  double max_condition = 100.0;        ///< > 1: xy covariance eigenvalue ratio that is degenerate
  int max_failures = 5;                ///< >= 0: consecutive failed scans reported degraded, then lost
  double max_position_3sigma_m = 5.0;  ///< > 0: 3 sigma (largest xy axis) beyond which: lost
  /// > 0: a pose farther than this from every map keyframe is outside the mapped path (check (f)).
  double max_keyframe_distance_m = 10.0;
};

/// Overrides from the keys of the `integrity:` section (names as the fields).
void loadParams(const YamlParams& yaml, IntegrityParams& params);

/// The chi^2 quantile with 3 degrees of freedom: P(X <= q) = p, p in (0, 1).
double chi2Quantile3(double p);

/// Covariance of the odometry motion `motion` (T_prev_cur) under the noise model, in its frame.
Eigen::Matrix3d odometryCovariance(const mrpt::math::TPose2D& motion, const IntegrityParams& params);

/// Covariance of the last keyframe's pose relative to the first along `path` (indices into
/// map.keyframes), in the map frame: the odometry noise model compounded over each step between
/// consecutive keyframes of the path. Zero for a path of fewer than two keyframes.
Eigen::Matrix3d pathCovariance(const KeyframeMap& map, const std::vector<std::size_t>& path,
                               const IntegrityParams& params);

/// (x, y, phi) of b - a in the map frame, phi wrapped to (-pi, pi].
Eigen::Vector3d poseDifference(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b);

/// Squared Mahalanobis norm v^T S^-1 v (S symmetric positive definite, else +inf).
double mahalanobis2(const Eigen::Vector3d& v, const Eigen::Matrix3d& s);

/// 3 sigma of the largest axis of the xy covariance.
double position3Sigma(const Eigen::Matrix3d& cov);

/// Ratio of the largest to the smallest eigenvalue of the xy covariance.
double xyCondition(const Eigen::Matrix3d& cov);

/// Check (f): where `pose` lies relative to the map's keyframes.
struct MapCoverage {
  long keyframe = -1;             ///< index of the nearest keyframe (-1: the map has none)
  double distance_m = 0;          ///< to it
  bool outside = false;           ///< distance_m > params.max_keyframe_distance_m
  Eigen::Matrix3d extra_cov       ///< if outside: the odometry noise model over the lever from the
      = Eigen::Matrix3d::Zero();  ///< keyframe to the pose, in the map frame (else zero)
};
MapCoverage mapCoverage(const KeyframeMap& map, const mrpt::math::TPose2D& pose,
                        const IntegrityParams& params);

/// Information-filter fusion of two estimates of the same pose (map frame).
void fusePoses(const mrpt::math::TPose2D& a, const Eigen::Matrix3d& cov_a, const mrpt::math::TPose2D& b,
               const Eigen::Matrix3d& cov_b, mrpt::math::TPose2D& out, Eigen::Matrix3d& cov_out);

/// Check (b): running median and MAD of accepted fit scores.
class FitMonitor {
 public:
  explicit FitMonitor(const IntegrityParams& params) : params_(params) {}
  /// True when `fit` is a drop well below the recent scores (needs fit_history / 2 scores).
  bool drop(double fit) const;
  void add(double fit);
  void clear() { fits_.clear(); }

 private:
  IntegrityParams params_;
  std::deque<double> fits_;
};

/// Check (e): odometry motions and reported poses of the recent scans.
class MotionWindow {
 public:
  explicit MotionWindow(const IntegrityParams& params) : params_(params) {}
  /// Adds the scan's odometry motion (before the check of the scan).
  void addMotion(const mrpt::math::TPose2D& motion, const Eigen::Matrix3d& cov);
  /// Squared Mahalanobis norm of (map motion since the oldest registered pose in the window) against
  /// the odometry over the same scans, for a registration `pose`, `cov` of the current scan; < 0
  /// when the window holds no registered pose.
  double test(const mrpt::math::TPose2D& pose, const Eigen::Matrix3d& cov) const;
  /// Records the current scan's outcome: a registration that passed the checks or not.
  void addPose(bool registered, const mrpt::math::TPose2D& pose, const Eigen::Matrix3d& cov);
  void clear() { entries_.clear(); }

 private:
  struct Entry {
    mrpt::math::TPose2D motion;  ///< odometry from the previous scan to this one
    Eigen::Matrix3d motion_cov;
    bool registered = false;
    mrpt::math::TPose2D pose;
    Eigen::Matrix3d cov;
  };
  IntegrityParams params_;
  std::deque<Entry> entries_;
};

}  // namespace radarslam
