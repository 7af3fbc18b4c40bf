#include "radarslam/dds/pose_publisher.h"

#include <cmath>

namespace radarslam::dds {

PosePublisher::PosePublisher(Domain& domain, const std::string& topic, const std::string& frame_id)
    : pub_(domain, topic, TopicQos::stream(10)), frame_id_(frame_id) {}

PoseWithCovarianceStampedMsg PosePublisher::makeMessage(StampNs stamp, const mrpt::math::TPose2D& pose,
                                                        const std::array<double, 9>& cov,
                                                        const std::string& frame_id) {
  PoseWithCovarianceStampedMsg m;
  m.header = {toTimeMsg(stamp), frame_id};
  m.pose.x = pose.x;
  m.pose.y = pose.y;
  m.pose.qz = std::sin(pose.phi / 2);
  m.pose.qw = std::cos(pose.phi / 2);
  // 6x6 indices of x, y, rot z; the rest of the diagonal (z, rot x, rot y) is "not estimated".
  constexpr int kIdx[3] = {0, 1, 5};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m.covariance[kIdx[r] * 6 + kIdx[c]] = cov[r * 3 + c];
  for (int d : {2, 3, 4}) m.covariance[d * 6 + d] = 1e6;
  return m;
}

void PosePublisher::publish(StampNs stamp, const mrpt::math::TPose2D& pose,
                            const std::array<double, 9>& cov) {
  pub_.publish(makeMessage(stamp, pose, cov, frame_id_));
}

mrpt::math::TPose2D poseFromMessage(const PoseWithCovarianceStampedMsg& msg) {
  const auto& p = msg.pose;
  const double yaw = std::atan2(2.0 * (p.qw * p.qz + p.qx * p.qy), 1.0 - 2.0 * (p.qy * p.qy + p.qz * p.qz));
  return {p.x, p.y, yaw};
}

}  // namespace radarslam::dds
