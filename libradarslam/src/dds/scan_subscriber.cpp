#include "radarslam/dds/scan_subscriber.h"

namespace radarslam::dds {

ScanSubscriber::ScanSubscriber(Domain& domain, const std::string& topic, std::int32_t depth)
    : sub_(domain, topic, TopicQos::stream(depth)), filter_(topic) {}

CObservationRadarScan::Ptr ScanSubscriber::next(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    auto msg = sub_.take(std::max(left, std::chrono::milliseconds(0)));
    if (!msg) return nullptr;
    if (auto scan = filter_.accept(*msg)) return scan;
  }
}

}  // namespace radarslam::dds
