// 3D sensor pose -> SE(2) in the sensor's angle convention (see ground_truth.h).
#include <cmath>

#include "radarslam/io/ground_truth.h"

namespace radarslam {

mrpt::math::TPose2D projectSensorPoseToSE2(const mrpt::poses::CPose3D& world_sensor) {
  const auto R = world_sensor.getRotationMatrix();
  double x = world_sensor.x(), y = world_sensor.y();
  double r00 = R(0, 0), r10 = R(1, 0);
  if (R(2, 2) < 0.0) {
    // The sensor's z axis points down: flip the world (x, -y, -z) so it points up there, and the
    // SE(2) yaw grows from the sensor's x towards its y, like the azimuth angle.
    y = -y;
    r10 = -r10;
  }
  return {x, y, std::atan2(r10, r00)};
}

}  // namespace radarslam
