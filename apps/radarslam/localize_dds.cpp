#include "localize_dds.h"

#include <array>
#include <cmath>
#include <thread>

#include <Eigen/Eigenvalues>

#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/dds/domain.h>
#include <radarslam/dds/pose_publisher.h>
#include <radarslam/dds/scan_subscriber.h>

namespace radarslam::cli {

namespace {
std::chrono::milliseconds toMs(double s) {
  return std::chrono::milliseconds(static_cast<long long>(s * 1000));
}
}  // namespace

std::optional<std::string> ddsScanTopic(const std::string& dir) {
  const std::string prefix = "dds:";
  if (dir.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  const std::string topic = dir.substr(prefix.size());
  return topic.empty() ? std::string(dds::kRadarScanTopic) : topic;
}

const char* ddsPoseTopic() { return dds::kPoseTopic; }
const char* ddsStatusTopic() { return dds::kLocalizationStatusTopic; }

LocalizeDds::LocalizeDds(const LocalizeDdsOptions& options) : options_(options) {
  if (options_.domain_id > dds::kMaxDomainId)
    throw InputError("radarslam localize", "--domain must be 0.." + std::to_string(dds::kMaxDomainId));
  if (!(options_.timeout_s > 0)) throw InputError("radarslam localize", "--dds-timeout must be > 0");
  if (options_.scan_queue < 1 || options_.scan_queue > 1000)
    throw InputError("radarslam localize", "--scan-queue must be 1..1000");
  domain_ = std::make_unique<dds::Domain>(
      options_.domain_id, options_.config_file.empty() ? std::string(dds::kLoopbackConfigXml)
                                                       : dds::readConfigFile(options_.config_file));
  if (options_.publish) {
    poses_ = std::make_unique<dds::PosePublisher>(*domain_);
    status_ = std::make_unique<dds::Publisher<dds::LocalizationStatusMsg>>(
        *domain_, dds::kLocalizationStatusTopic, dds::TopicQos::stream(10));
  }
}

LocalizeDds::~LocalizeDds() = default;

bool LocalizeDds::waitForPoseSubscribers() {
  if (!poses_ || options_.wait_subscribers == 0) return true;
  const auto deadline = std::chrono::steady_clock::now() + toMs(options_.timeout_s);
  while (poses_->matchedSubscriptions() < options_.wait_subscribers ||
         status_->matchedSubscriptions() < options_.wait_subscribers) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

void LocalizeDds::startScans() {
  if (options_.scan_topic && !scans_)
    scans_ = std::make_unique<dds::ScanSubscriber>(*domain_, *options_.scan_topic, options_.scan_queue);
}

CObservationRadarScan::Ptr LocalizeDds::nextScan() {
  return scans_ ? scans_->next(toMs(options_.timeout_s)) : nullptr;
}

void LocalizeDds::publishPose(StampNs stamp, const mrpt::math::TPose2D& pose,
                              const Eigen::Matrix3d& covariance) {
  if (!poses_) return;
  std::array<double, 9> cov{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) cov[static_cast<std::size_t>(3 * r + c)] = covariance(r, c);
  poses_->publish(stamp, pose, cov);
  ++published_;
}

void LocalizeDds::publishStatus(const LocalizationResult& r, std::size_t global_fixes, bool pose_published) {
  if (!status_) return;
  dds::LocalizationStatusMsg m;
  m.header = {dds::toTimeMsg(r.stamp), "map"};
  m.status = toString(r.status);
  m.level = r.status == LocalizationStatus::Lost ? 2 : r.status == LocalizationStatus::Degraded ? 1 : 0;
  m.check = r.check;
  m.pose_published = pose_published;
  m.keyframe = r.localised ? static_cast<std::int32_t>(r.keyframe) : -1;
  m.fit_score = r.fit_score;
  m.inliers = static_cast<std::uint32_t>(r.inliers);
  if (r.localised) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(r.covariance.topLeftCorner<2, 2>());
    m.sigma_xy_m = std::sqrt(std::max(0.0, es.eigenvalues()(1)));
    m.sigma_yaw_rad = std::sqrt(std::max(0.0, r.covariance(2, 2)));
  }
  m.global_fixes = static_cast<std::uint32_t>(global_fixes);
  status_->publish(m);
}

void LocalizeDds::flush() {
  if (poses_ && poses_->matchedSubscriptions() > 0 &&
      !poses_->waitForAcknowledgements(toMs(options_.timeout_s)))
    logger().logFmt(mrpt::system::LVL_WARN, "localize: not every pose subscriber acknowledged all poses");
  if (status_ && status_->matchedSubscriptions() > 0 &&
      !status_->waitForAcknowledgements(toMs(options_.timeout_s)))
    logger().logFmt(mrpt::system::LVL_WARN,
                    "localize: not every status subscriber acknowledged all statuses");
}

}  // namespace radarslam::cli
