#pragma once
// The DDS side of `radarslam localize` (docs/dds.md): publishing the localised poses on
// rt/radarslam/pose and every scan's integrity status on rt/radarslam/localization_status
// (--publish), and a live scan source (DIR = "dds:" or "dds:TOPIC") that takes
// radarslam/RadarScan messages until no scan arrived for --dds-timeout seconds.
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

#include <radarslam/core/time.h>
#include <radarslam/obs/CObservationRadarScan.h>
#include <radarslam/reloc/localizer.h>

namespace radarslam::dds {
class Domain;
class PosePublisher;
template <class Msg>
class Publisher;
struct LocalizationStatusMsg;
class ScanSubscriber;
}  // namespace radarslam::dds

namespace radarslam::cli {

/// "dds:" -> the default scan topic, "dds:TOPIC" -> TOPIC; nullopt if `dir` is not a DDS source.
std::optional<std::string> ddsScanTopic(const std::string& dir);
/// The topic --publish sends the poses on (rt/radarslam/pose).
const char* ddsPoseTopic();
/// The topic --publish sends every scan's status on (rt/radarslam/localization_status).
const char* ddsStatusTopic();

struct LocalizeDdsOptions {
  bool publish = false;                   ///< --publish
  std::optional<std::string> scan_topic;  ///< set: scans come from DDS (DIR = dds:[TOPIC])
  std::uint32_t domain_id = 0;            ///< --domain
  std::string config_file;                ///< --dds-config (empty: built-in loopback XML)
  double timeout_s = 5.0;                 ///< --dds-timeout: end of the scan stream
  std::uint32_t wait_subscribers = 0;     ///< --wait-subscribers: pose subscribers to wait for
  std::int32_t scan_queue = 4;            ///< --scan-queue: unread scans kept (KEEP_LAST), older ones dropped
};

/// One DDS participant for the localiser; exists only when poses are published or scans received.
class LocalizeDds {
 public:
  explicit LocalizeDds(const LocalizeDdsOptions& options);
  ~LocalizeDds();

  /// Waits (at most --dds-timeout) for --wait-subscribers subscribers of the poses and of the
  /// status; false on timeout.
  bool waitForPoseSubscribers();
  /// Starts receiving scans (call when ready to localise: scans sent before are not buffered).
  void startScans();
  /// The next scan, or nullptr once no scan arrived for --dds-timeout seconds.
  CObservationRadarScan::Ptr nextScan();
  /// Publishes one localised pose (no-op without --publish); covariance of (x, y, phi).
  void publishPose(StampNs stamp, const mrpt::math::TPose2D& pose, const Eigen::Matrix3d& covariance);
  /// Publishes the scan's status (no-op without --publish); `pose_published`: publishPose was
  /// called for it.
  void publishStatus(const LocalizationResult& result, std::size_t global_fixes, bool pose_published);
  /// Waits until the subscribers acknowledged every pose and status (before the process exits).
  void flush();
  std::size_t posesPublished() const { return published_; }

 private:
  LocalizeDdsOptions options_;
  std::unique_ptr<dds::Domain> domain_;
  std::unique_ptr<dds::PosePublisher> poses_;
  std::unique_ptr<dds::Publisher<dds::LocalizationStatusMsg>> status_;
  std::unique_ptr<dds::ScanSubscriber> scans_;
  std::size_t published_ = 0;
};

}  // namespace radarslam::cli
