#pragma once
// Motion distortion compensation of keypoints (not in the paper); builds on the radar module's
// SE(2) twist integration (radar/motion_compensation.h), which compensates peak clouds. A spinning radar
// fires its azimuths over a whole sweep (~250 ms at 4 Hz), during which the vehicle moves metres; a return
// seen at azimuth a was measured from where the sensor was at that azimuth's firing time. With the current
// velocity estimate (constant over the sweep) each point is moved into the sensor frame at the
// scan's reference time (CObservationRadarScan::refStampNs(), mid-sweep):
//   p_ref = exp(xi * dt_a) (+) p,   dt_a = t_a - t_ref.
#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>

#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"
#include "radarslam/radar/motion_compensation.h"

namespace radarslam {

/// integrateTwist (radar/motion_compensation.h) as an MRPT pose.
mrpt::math::TPose2D twistToPose(const BodyVelocity& v, double dt);
/// Inverse of integrateTwist for dt: the constant twist that moves by `delta` in `dt` seconds.
BodyVelocity twistFromDelta(const mrpt::math::TPose2D& delta, double dt);

/// Firing time of each direction of one sweep, relative to the scan's reference time.
class AzimuthClock {
 public:
  AzimuthClock() = default;
  explicit AzimuthClock(const CObservationRadarScan& scan);
  /// Seconds from the reference time to when the beam through direction `angle_rad` fired
  /// (nearest azimuth). 0 for a scan without stamps.
  double offsetSeconds(double angle_rad) const;

 private:
  std::vector<double> offsets_s_;  ///< per bucket of angle
  double bucket_rad_ = 0.0;
};

/// p measured at `dt` seconds from the reference time, expressed in the reference frame.
Eigen::Vector2d compensatePoint(const Eigen::Vector2d& p, double dt, const BodyVelocity& v);
/// Inverse of compensatePoint: where a reference-time point appears in a scan fired at `dt`.
Eigen::Vector2d decompensatePoint(const Eigen::Vector2d& p_ref, double dt, const BodyVelocity& v);

}  // namespace radarslam
