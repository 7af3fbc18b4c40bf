#pragma once
// Publishes the localiser's pose as geometry_msgs/PoseWithCovarianceStamped (frame "map") on
// rt/radarslam/pose (ROS 2: /radarslam/pose). Stream QoS: RELIABLE, VOLATILE, KEEP_LAST 10.
#include <mrpt/math/TPose2D.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>

#include "radarslam/dds/domain.h"

namespace radarslam::dds {

class PosePublisher {
 public:
  explicit PosePublisher(Domain& domain, const std::string& topic = kPoseTopic,
                         const std::string& frame_id = "map");
  /// `covariance_xyphi`: 3x3 row-major over (x, y, phi), placed at (x, y, rot z) of the 6x6
  /// ROS covariance; z, rot x, rot y get a large variance (1e6) as they are not estimated.
  void publish(StampNs stamp, const mrpt::math::TPose2D& pose, const std::array<double, 9>& covariance_xyphi);
  std::uint32_t matchedSubscriptions() const { return pub_.matchedSubscriptions(); }
  /// Blocks until every reliable subscriber acknowledged all poses (or the timeout); true if so.
  bool waitForAcknowledgements(std::chrono::milliseconds timeout) const {
    return pub_.waitForAcknowledgements(timeout);
  }

  /// The message publish() sends (exposed for tests and other transports).
  static PoseWithCovarianceStampedMsg makeMessage(StampNs stamp, const mrpt::math::TPose2D& pose,
                                                  const std::array<double, 9>& covariance_xyphi,
                                                  const std::string& frame_id);

 private:
  Publisher<PoseWithCovarianceStampedMsg> pub_;
  std::string frame_id_;
};

/// The planar pose (x, y, yaw) of a message.
mrpt::math::TPose2D poseFromMessage(const PoseWithCovarianceStampedMsg& msg);

}  // namespace radarslam::dds
