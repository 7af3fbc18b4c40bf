#include "radarslam/dds/scan_subscriber.h"

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/dds/scan_messages.h"

namespace radarslam::dds {

ScanSubscriber::ScanSubscriber(Domain& domain, const std::string& topic, std::int32_t depth)
    : sub_(domain, topic, TopicQos::stream(depth)) {}

CObservationRadarScan::Ptr ScanSubscriber::next(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    auto msg = sub_.take(std::max(left, std::chrono::milliseconds(0)));
    if (!msg) return nullptr;
    try {
      return scanFromMessage(*msg);
    } catch (const InputError& e) {
      logger().logFmt(mrpt::system::LVL_WARN, "skipping a radar scan: %s", e.what());
    }
  }
}

}  // namespace radarslam::dds
