#include "radarslam/frontend/motion_compensation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radarslam {

mrpt::math::TPose2D twistToPose(const BodyVelocity& v, double dt) {
  const RigidTransform2D t = integrateTwist(v, dt);
  return {t.x, t.y, t.theta};
}

BodyVelocity twistFromDelta(const mrpt::math::TPose2D& delta, double dt) {
  if (!(dt > 0)) return {};
  const double th = delta.phi;
  double a = 1.0, b = 0.0;
  if (std::abs(th) > 1e-9) {
    a = std::sin(th) / th;
    b = (1.0 - std::cos(th)) / th;
  }
  // Invert the 2x2 V matrix.
  const double det = a * a + b * b;
  const double tx = (a * delta.x + b * delta.y) / det;
  const double ty = (-b * delta.x + a * delta.y) / det;
  return {tx / dt, ty / dt, th / dt};
}

AzimuthClock::AzimuthClock(const CObservationRadarScan& scan) {
  const std::size_t n = scan.num_azimuths;
  if (n == 0 || scan.azimuth_stamps_ns.size() != n || scan.azimuth_angles_rad.size() != n) return;
  const StampNs ref = scan.refStampNs();
  // Lookup table over [0, 2pi): each bucket takes the nearest azimuth's firing time.
  const std::size_t buckets = std::max<std::size_t>(4 * n, 360);
  bucket_rad_ = 2.0 * std::numbers::pi / static_cast<double>(buckets);
  offsets_s_.assign(buckets, 0.0);
  std::vector<double> best(buckets, 1e9);
  const double two_pi = 2.0 * std::numbers::pi;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = std::fmod(std::fmod(scan.azimuth_angles_rad[i], two_pi) + two_pi, two_pi);
    const double dt = toSeconds(scan.azimuth_stamps_ns[i] - ref);
    // Each azimuth claims the buckets within one azimuth spacing of it.
    const int reach = static_cast<int>(std::ceil(two_pi / static_cast<double>(n) / bucket_rad_)) + 1;
    const int centre = static_cast<int>(std::lround(a / bucket_rad_));
    for (int k = centre - reach; k <= centre + reach; ++k) {
      const std::size_t idx = static_cast<std::size_t>((k % static_cast<int>(buckets) + buckets) % buckets);
      double d = std::abs(std::remainder(a - idx * bucket_rad_, two_pi));
      if (d < best[idx]) {
        best[idx] = d;
        offsets_s_[idx] = dt;
      }
    }
  }
}

double AzimuthClock::offsetSeconds(double angle_rad) const {
  if (offsets_s_.empty()) return 0.0;
  const double two_pi = 2.0 * std::numbers::pi;
  const double a = std::fmod(std::fmod(angle_rad, two_pi) + two_pi, two_pi);
  const std::size_t idx = static_cast<std::size_t>(std::lround(a / bucket_rad_)) % offsets_s_.size();
  return offsets_s_[idx];
}

Eigen::Vector2d compensatePoint(const Eigen::Vector2d& p, double dt, const BodyVelocity& v) {
  double x, y;
  integrateTwist(v, dt).apply(p.x(), p.y(), x, y);
  return {x, y};
}

Eigen::Vector2d decompensatePoint(const Eigen::Vector2d& p_ref, double dt, const BodyVelocity& v) {
  const auto T = mrpt::math::TPose2D(0, 0, 0) - twistToPose(v, dt);
  const double c = std::cos(T.phi), s = std::sin(T.phi);
  return {c * p_ref.x() - s * p_ref.y() + T.x, s * p_ref.x() + c * p_ref.y() + T.y};
}

}  // namespace radarslam
