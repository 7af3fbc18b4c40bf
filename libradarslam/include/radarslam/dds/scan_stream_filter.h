#pragma once
// The gate every live radar scan sample passes (docs/dds.md, "Radar scan input"): the message is
// converted and checked (scanFromMessage: sizes, checkScanPlausible), and its reference stamp must
// be after the previous accepted scan's. A bad sample is dropped with a rate-limited warning
// naming the topic and the problem: a live stream does not die on one bad sample.
#include <chrono>
#include <cstdint>
#include <string>

#include "radarslam/dds/messages.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::dds {

class ScanStreamFilter {
 public:
  explicit ScanStreamFilter(std::string topic,
                            std::chrono::steady_clock::duration warn_interval = std::chrono::seconds(10));

  /// The scan of `msg`, or nullptr if the sample is dropped.
  CObservationRadarScan::Ptr accept(const RadarScanMsg& msg);

  std::uint64_t accepted() const { return accepted_; }
  std::uint64_t dropped() const { return dropped_; }
  /// The problem of the last dropped sample ("" if none was dropped).
  const std::string& lastProblem() const { return last_problem_; }
  /// Warnings logged so far (the first drop, then at most one per warn interval).
  std::uint64_t warnings() const { return warnings_; }

 private:
  void drop(const std::string& problem);

  std::string topic_;
  std::chrono::steady_clock::duration warn_interval_;
  std::chrono::steady_clock::time_point last_warning_{};
  std::uint64_t accepted_ = 0, dropped_ = 0, warnings_ = 0, dropped_since_warning_ = 0;
  bool have_last_stamp_ = false;
  StampNs last_stamp_ = 0;
  std::string last_problem_;
};

}  // namespace radarslam::dds
