#pragma once
// A live radar scan source over DDS: takes radarslam/RadarScan messages (default topic
// rt/radarslam/radar_scan) and yields CObservationRadarScan, e.g. for `radarslam localize`.
// Stream QoS (RELIABLE, VOLATILE, KEEP_LAST depth): if the consumer is slower than the radar,
// the oldest unread scans are dropped.
#include <chrono>
#include <string>

#include "radarslam/dds/domain.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::dds {

class ScanSubscriber {
 public:
  explicit ScanSubscriber(Domain& domain, const std::string& topic = kRadarScanTopic, std::int32_t depth = 4);
  /// Blocks until the next scan or the timeout; nullptr on timeout. A malformed message is
  /// logged (WARN) and skipped.
  CObservationRadarScan::Ptr next(std::chrono::milliseconds timeout);
  std::uint32_t matchedPublishers() const { return sub_.matchedPublications(); }

 private:
  Subscription<RadarScanMsg> sub_;
};

}  // namespace radarslam::dds
