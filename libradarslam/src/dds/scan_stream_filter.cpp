#include "radarslam/dds/scan_stream_filter.h"

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/dds/scan_messages.h"

namespace radarslam::dds {

ScanStreamFilter::ScanStreamFilter(std::string topic, std::chrono::steady_clock::duration warn_interval)
    : topic_(std::move(topic)), warn_interval_(warn_interval) {}

CObservationRadarScan::Ptr ScanStreamFilter::accept(const RadarScanMsg& msg) {
  CObservationRadarScan::Ptr scan;
  try {
    scan = scanFromMessage(msg);
  } catch (const InputError& e) {
    drop(e.problem());
    return nullptr;
  }
  const StampNs t = scan->refStampNs();
  if (have_last_stamp_ && t <= last_stamp_) {
    drop("stamp " + std::to_string(t) + " ns is not after the previous scan's (" +
         std::to_string(last_stamp_) + " ns)");
    return nullptr;
  }
  have_last_stamp_ = true;
  last_stamp_ = t;
  ++accepted_;
  return scan;
}

void ScanStreamFilter::drop(const std::string& problem) {
  ++dropped_;
  ++dropped_since_warning_;
  last_problem_ = problem;
  const auto now = std::chrono::steady_clock::now();
  if (warnings_ > 0 && now - last_warning_ < warn_interval_) return;
  if (warnings_ == 0)
    logger().logFmt(mrpt::system::LVL_WARN, "%s: dropping a radar scan: %s", topic_.c_str(), problem.c_str());
  else
    logger().logFmt(mrpt::system::LVL_WARN, "%s: dropped %llu radar scans since the last warning; latest: %s",
                    topic_.c_str(), static_cast<unsigned long long>(dropped_since_warning_), problem.c_str());
  ++warnings_;
  dropped_since_warning_ = 0;
  last_warning_ = now;
}

}  // namespace radarslam::dds
