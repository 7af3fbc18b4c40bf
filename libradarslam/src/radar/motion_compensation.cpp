#include "radarslam/radar/motion_compensation.h"

#include <cmath>
#include <string>

#include "radarslam/core/errors.h"

namespace radarslam {

void RigidTransform2D::apply(double px, double py, double& qx, double& qy) const {
  const double c = std::cos(theta), s = std::sin(theta);
  qx = c * px - s * py + x;
  qy = s * px + c * py + y;
}

RigidTransform2D integrateTwist(const BodyVelocity& v, double dt_s) {
  // exp([u; w]) for u = v * dt, w = omega * dt: translation V(w) u with
  // V = [[sin w / w, -(1 - cos w) / w], [(1 - cos w) / w, sin w / w]] (Taylor series near w = 0).
  const double w = v.omega * dt_s, ux = v.vx * dt_s, uy = v.vy * dt_s;
  double a, b;  // sin(w)/w, (1 - cos(w))/w
  if (std::abs(w) < 1e-9) {
    a = 1.0;
    b = w / 2.0;
  } else {
    const double h = std::sin(w / 2.0);
    a = std::sin(w) / w;
    b = 2.0 * h * h / w;  // = (1 - cos w) / w without cancellation
  }
  return {a * ux - b * uy, b * ux + a * uy, w};
}

void compensateMotion(std::span<RadarPoint> points, const CObservationRadarScan& scan,
                      const BodyVelocity& v) {
  if (points.empty()) return;
  if (scan.azimuth_stamps_ns.size() != scan.num_azimuths)
    throw InputError("radar scan", "motion compensation needs one stamp per azimuth");
  const StampNs ref = scan.refStampNs();
  // One transform per azimuth (all points of an azimuth share its firing time).
  std::vector<RigidTransform2D> per_azimuth(scan.num_azimuths);
  std::vector<char> done(scan.num_azimuths, 0);
  for (RadarPoint& p : points) {
    if (p.azimuth >= scan.num_azimuths)
      throw InputError("radar scan", "point azimuth " + std::to_string(p.azimuth) + " is not in a scan of " +
                                         std::to_string(scan.num_azimuths) + " azimuths");
    if (!done[p.azimuth]) {
      per_azimuth[p.azimuth] = integrateTwist(v, toSeconds(scan.azimuth_stamps_ns[p.azimuth] - ref));
      done[p.azimuth] = 1;
    }
    double qx, qy;
    per_azimuth[p.azimuth].apply(p.x, p.y, qx, qy);
    p.x = static_cast<float>(qx);
    p.y = static_cast<float>(qy);
    p.range_m = static_cast<float>(std::hypot(qx, qy));
  }
}

}  // namespace radarslam
