#include "radarslam/eval/yaw_dynamics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace radarslam::eval {

namespace {
double percentile(std::vector<double> v, double q) {
  const auto k = static_cast<std::size_t>(std::floor(q * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}
}  // namespace

YawDynamics yawDynamics(const Trajectory& poses) {
  if (poses.size() < 3) throw std::invalid_argument("yaw dynamics need at least 3 poses");
  constexpr double kDeg = 180.0 / M_PI;
  std::vector<double> rate, mid_time;  // rad/s, s
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const double dt = toSeconds(poses[k].stamp - poses[k - 1].stamp);
    if (!(dt > 0)) throw std::invalid_argument("yaw dynamics need increasing stamps");
    rate.push_back(std::remainder(poses[k].pose.phi - poses[k - 1].pose.phi, 2 * M_PI) / dt);
    mid_time.push_back(toSeconds(poses[k - 1].stamp - poses.front().stamp) + dt / 2);
  }
  std::vector<double> abs_rate(rate.size()), abs_accel;
  std::transform(rate.begin(), rate.end(), abs_rate.begin(), [&](double r) { return std::abs(r) * kDeg; });
  for (std::size_t k = 1; k < rate.size(); ++k)
    abs_accel.push_back(std::abs(rate[k] - rate[k - 1]) / (mid_time[k] - mid_time[k - 1]) * kDeg);
  YawDynamics d;
  d.samples = abs_accel.size();
  d.rate_p99_dps = percentile(abs_rate, 0.99);
  d.rate_max_dps = *std::max_element(abs_rate.begin(), abs_rate.end());
  d.accel_p95_dps2 = percentile(abs_accel, 0.95);
  d.accel_p99_dps2 = percentile(abs_accel, 0.99);
  d.accel_max_dps2 = *std::max_element(abs_accel.begin(), abs_accel.end());
  return d;
}

}  // namespace radarslam::eval
