#pragma once
// Motion compensation of a radar sweep. A Navtech sweep takes ~250 ms, so at 10 m/s the first
// and last azimuths are fired 2.5 m apart. Assuming a constant body velocity (vx, vy, omega) in
// the sensor frame over the sweep, the sensor pose at time t relative to its pose at the scan's
// reference time t_ref (CObservationRadarScan::refStampNs()) is the SE(2) exponential of the
// twist times (t - t_ref); a point measured at time t is moved into the reference frame by it.
#include <span>
#include <vector>

#include "radarslam/core/time.h"
#include "radarslam/obs/CObservationRadarScan.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

/// Constant body-frame velocity of the sensor: m/s along its x and y axes, rad/s about z.
struct BodyVelocity {
  double vx = 0.0, vy = 0.0, omega = 0.0;
};

/// A 2-D rigid transform p' = R(theta) p + t.
struct RigidTransform2D {
  double x = 0.0, y = 0.0, theta = 0.0;
  void apply(double px, double py, double& qx, double& qy) const;
};

/// Exact SE(2) exponential of the twist `v` integrated over `dt_s` seconds: the sensor pose after
/// dt_s expressed in the sensor frame at the start (dt_s may be negative).
RigidTransform2D integrateTwist(const BodyVelocity& v, double dt_s);

/// Moves every point from its azimuth's firing time (scan.azimuth_stamps_ns[point.azimuth]) to
/// the scan's reference time: the result is the point in the sensor frame at refStampNs().
/// range_m is updated to the new distance from the sensor; power and azimuth are kept.
/// Throws InputError if a point's azimuth index is not in the scan.
void compensateMotion(std::span<RadarPoint> points, const CObservationRadarScan& scan, const BodyVelocity& v);

inline std::vector<RadarPoint> motionCompensated(std::vector<RadarPoint> points,
                                                 const CObservationRadarScan& scan, const BodyVelocity& v) {
  compensateMotion(points, scan, v);
  return points;
}

}  // namespace radarslam
