// Integrity checks of map-based localisation; see reloc/integrity.h.
#include "radarslam/reloc/integrity.h"

#include <mrpt/poses/CPose2D.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/map/keyframe_search.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, IntegrityParams& p) {
  yaml.get("enabled", p.enabled);
  yaml.get("odom_sigma_per_m", p.odom_sigma_per_m, Range::closed(0, 1));
  yaml.get("odom_sigma_floor_m", p.odom_sigma_floor_m, Range::closed(0, 100));
  yaml.get("odom_sigma_rad_per_rad", p.odom_sigma_rad_per_rad, Range::closed(0, 1));
  yaml.get("odom_sigma_rad_per_m", p.odom_sigma_rad_per_m, Range::closed(0, 1));
  yaml.get("odom_sigma_floor_rad", p.odom_sigma_floor_rad, Range::closed(0, 3.2));
  if (!(p.odom_sigma_floor_m + p.odom_sigma_floor_rad > 0))
    yaml.fail("odom_sigma_floor_m", "odom_sigma_floor_m and odom_sigma_floor_rad must not both be 0");
  yaml.get("chi2_probability", p.chi2_probability, Range::above(0.5, 0.999999));
  yaml.get("window_scans", p.window_scans, Range::closed(0, 10000));
  if (p.window_scans == 1) yaml.fail("window_scans", "must be 0 (off) or >= 2");
  yaml.get("fit_history", p.fit_history, Range::closed(5, 100000));
  yaml.get("fit_drop_sigmas", p.fit_drop_sigmas, Range::above(0, 1000));
  yaml.get("min_fit_sigma", p.min_fit_sigma, Range::above(0, 1));
  yaml.get("max_condition", p.max_condition, Range::above(1, 1e12));
  yaml.get("max_failures", p.max_failures, Range::closed(0, 1000000));
  yaml.get("max_position_3sigma_m", p.max_position_3sigma_m, Range::above(0, 1e6));
  yaml.get("max_keyframe_distance_m", p.max_keyframe_distance_m, Range::above(0, 1e6));
}

double chi2Quantile3(double p) {
  // CDF of chi^2(3): erf(sqrt(x/2)) - sqrt(2x/pi) exp(-x/2); monotone, bisection.
  auto cdf = [](double x) { return std::erf(std::sqrt(x / 2)) - std::sqrt(2 * x / M_PI) * std::exp(-x / 2); };
  double lo = 0, hi = 1000;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Eigen::Matrix3d odometryCovariance(const mrpt::math::TPose2D& m, const IntegrityParams& p) {
  const double d = std::hypot(m.x, m.y);
  const double st = p.odom_sigma_floor_m + p.odom_sigma_per_m * d;
  const double sr =
      p.odom_sigma_floor_rad + p.odom_sigma_rad_per_rad * std::abs(m.phi) + p.odom_sigma_rad_per_m * d;
  return Eigen::Vector3d(st * st, st * st, sr * sr).asDiagonal();
}

Eigen::Matrix3d pathCovariance(const KeyframeMap& map, const std::vector<std::size_t>& path,
                               const IntegrityParams& params) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t i = 1; i < path.size(); ++i) {
    const mrpt::math::TPose2D& at = map.keyframes[path[i - 1]].pose;
    const mrpt::math::TPose2D rel =
        (mrpt::poses::CPose2D(map.keyframes[path[i]].pose) - mrpt::poses::CPose2D(at)).asTPose();
    cov = composeCovariance(at, cov, rel, odometryCovariance(rel, params));
  }
  return cov;
}

Eigen::Vector3d poseDifference(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) {
  return {b.x - a.x, b.y - a.y, std::remainder(b.phi - a.phi, 2 * M_PI)};
}

double mahalanobis2(const Eigen::Vector3d& v, const Eigen::Matrix3d& s) {
  const Eigen::LLT<Eigen::Matrix3d> llt(0.5 * (s + s.transpose()));
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return v.dot(llt.solve(v));
}

double position3Sigma(const Eigen::Matrix3d& cov) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov.topLeftCorner<2, 2>());
  return 3 * std::sqrt(std::max(0.0, es.eigenvalues()(1)));
}

double xyCondition(const Eigen::Matrix3d& cov) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov.topLeftCorner<2, 2>());
  const double lo = es.eigenvalues()(0), hi = es.eigenvalues()(1);
  return lo > 0 ? hi / lo : std::numeric_limits<double>::infinity();
}

void fusePoses(const mrpt::math::TPose2D& a, const Eigen::Matrix3d& cov_a, const mrpt::math::TPose2D& b,
               const Eigen::Matrix3d& cov_b, mrpt::math::TPose2D& out, Eigen::Matrix3d& cov_out) {
  // Kalman update of a by the measurement b: x = a + K (b - a), K = Pa (Pa + Pb)^-1.
  const Eigen::Matrix3d k = cov_a * (cov_a + cov_b).inverse();
  const Eigen::Vector3d x = k * poseDifference(a, b);
  out = {a.x + x(0), a.y + x(1), std::remainder(a.phi + x(2), 2 * M_PI)};
  cov_out = (Eigen::Matrix3d::Identity() - k) * cov_a;
  cov_out = 0.5 * (cov_out + cov_out.transpose()).eval();
}

bool FitMonitor::drop(double fit) const {
  if (fits_.size() < static_cast<std::size_t>(params_.fit_history) / 2) return false;
  std::vector<double> v(fits_.begin(), fits_.end());
  auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double median = *mid;
  for (double& x : v) x = std::abs(x - median);
  std::nth_element(v.begin(), mid, v.end());
  const double sigma = std::max(params_.min_fit_sigma, 1.4826 * *mid);
  return fit < median - params_.fit_drop_sigmas * sigma;
}

void FitMonitor::add(double fit) {
  fits_.push_back(fit);
  while (fits_.size() > static_cast<std::size_t>(params_.fit_history)) fits_.pop_front();
}

void MotionWindow::addMotion(const mrpt::math::TPose2D& motion, const Eigen::Matrix3d& cov) {
  if (params_.window_scans <= 0) return;
  entries_.push_back({motion, cov, false, {}, Eigen::Matrix3d::Zero()});
  while (entries_.size() > static_cast<std::size_t>(params_.window_scans) + 1) entries_.pop_front();
}

double MotionWindow::test(const mrpt::math::TPose2D& pose, const Eigen::Matrix3d& cov) const {
  if (entries_.size() < 2) return -1;
  std::size_t i = 0;
  while (i + 1 < entries_.size() && !entries_[i].registered) ++i;
  if (i + 1 >= entries_.size()) return -1;
  // Odometry from scan i to the current scan, in scan i's frame.
  mrpt::math::TPose2D odo{0, 0, 0};
  Eigen::Matrix3d odo_cov = Eigen::Matrix3d::Zero();
  for (std::size_t j = i + 1; j < entries_.size(); ++j) {
    odo_cov = composeCovariance(odo, odo_cov, entries_[j].motion, entries_[j].motion_cov);
    odo = (mrpt::poses::CPose2D(odo) + mrpt::poses::CPose2D(entries_[j].motion)).asTPose();
  }
  // Map motion: pose_i^-1 (+) pose, and its covariance from both registrations.
  const Entry& e = entries_[i];
  const double c = std::cos(e.pose.phi), s = std::sin(e.pose.phi);
  const double dx = pose.x - e.pose.x, dy = pose.y - e.pose.y;
  const mrpt::math::TPose2D rel{c * dx + s * dy, -s * dx + c * dy,
                                std::remainder(pose.phi - e.pose.phi, 2 * M_PI)};
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero(), b = Eigen::Matrix3d::Zero();
  a << -c, -s, -s * dx + c * dy, s, -c, -c * dx - s * dy, 0, 0, -1;
  b << c, s, 0, -s, c, 0, 0, 0, 1;
  const Eigen::Matrix3d rel_cov = a * e.cov * a.transpose() + b * cov * b.transpose();
  return mahalanobis2(poseDifference(odo, rel), odo_cov + rel_cov);
}

void MotionWindow::addPose(bool registered, const mrpt::math::TPose2D& pose, const Eigen::Matrix3d& cov) {
  if (entries_.empty()) return;
  entries_.back().registered = registered;
  entries_.back().pose = pose;
  entries_.back().cov = cov;
}

MapCoverage mapCoverage(const KeyframeMap& map, const mrpt::math::TPose2D& pose,
                        const IntegrityParams& params) {
  MapCoverage c;
  c.keyframe = nearestKeyframe(map, pose.x, pose.y);
  if (c.keyframe < 0) return c;
  const mrpt::math::TPose2D& kf = map.keyframes[static_cast<std::size_t>(c.keyframe)].pose;
  c.distance_m = std::hypot(kf.x - pose.x, kf.y - pose.y);
  c.outside = c.distance_m > params.max_keyframe_distance_m;
  if (c.outside) {
    const mrpt::math::TPose2D lever = (mrpt::poses::CPose2D(pose) - mrpt::poses::CPose2D(kf)).asTPose();
    c.extra_cov = composeCovariance(kf, Eigen::Matrix3d::Zero(), lever, odometryCovariance(lever, params));
  }
  return c;
}

}  // namespace radarslam
