#pragma once
// A live radar scan source over DDS: takes radarslam/RadarScan messages (default topic
// rt/radarslam/radar_scan) and yields CObservationRadarScan, e.g. for `radarslam localize`.
// Stream QoS (RELIABLE, VOLATILE, KEEP_LAST depth): if the consumer is slower than the radar,
// the oldest unread scans are dropped.
#include <chrono>
#include <string>

#include "radarslam/dds/domain.h"
#include "radarslam/dds/scan_stream_filter.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::dds {

class ScanSubscriber {
 public:
  explicit ScanSubscriber(Domain& domain, const std::string& topic = kRadarScanTopic, std::int32_t depth = 4);
  /// Blocks until the next scan or the timeout; nullptr on timeout. A malformed or implausible
  /// sample, or one not after the previous scan, is dropped (ScanStreamFilter: rate-limited WARN).
  CObservationRadarScan::Ptr next(std::chrono::milliseconds timeout);
  std::uint32_t matchedPublishers() const { return sub_.matchedPublications(); }
  /// Counts of accepted and dropped samples.
  const ScanStreamFilter& filter() const { return filter_; }

 private:
  Subscription<RadarScanMsg> sub_;
  ScanStreamFilter filter_;
};

}  // namespace radarslam::dds
