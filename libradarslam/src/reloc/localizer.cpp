// Localisation facade: odometry prediction, map tracking, global relocalisation; see
// reloc/localizer.h.
#include "radarslam/reloc/localizer.h"

#include <mrpt/poses/CPose2D.h>

#include <chrono>
#include <future>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/frontend/odometry.h"
#include "radarslam/radar/motion_compensation.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, LocalizerParams& p) {
  yaml.get("motion_compensation", p.motion_compensation);
  yaml.get("max_missed_scans", p.max_missed_scans);
  yaml.get("global_retry_interval", p.global_retry_interval);
  if (p.max_missed_scans < 0 || p.global_retry_interval < 1)
    throw InputError(yaml.origin(),
                     "localization: max_missed_scans must be >= 0, global_retry_interval >= 1");
  loadParams(yaml.section("peak_cloud"), p.peaks);
  loadParams(yaml.section("global"), p.global);
  loadParams(yaml.section("tracker"), p.tracker);
}

const char* toString(LocalizationStatus s) {
  switch (s) {
    case LocalizationStatus::GlobalFix:
      return "global_fix";
    case LocalizationStatus::Tracking:
      return "tracking";
    case LocalizationStatus::Lost:
      return "lost";
  }
  return "?";
}

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
mrpt::math::TPose2D compose(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) {
  return (mrpt::poses::CPose2D(a) + mrpt::poses::CPose2D(b)).asTPose();
}
}  // namespace

struct Localizer::Impl {
  LocalizerParams params;
  RadarOdometry odometry;
  GlobalLocalizer global;
  MapTracker tracker;
  bool have_pose = false;  ///< pose is trusted or dead-reckoned from a trusted one
  mrpt::math::TPose2D pose;
  int missed = 0;       ///< rejected registrations in a row
  long lost_scans = 0;  ///< scans since global localisation became necessary
  std::size_t fixes = 0;
  Impl(const KeyframeMap& map, const OdometryParams& op, const LocalizerParams& p)
      : params(p), odometry(op), global(map, p.global), tracker(map, p.tracker) {}
};

Localizer::Localizer(const KeyframeMap& map, const OdometryParams& odometry, const LocalizerParams& params)
    : impl_(std::make_unique<Impl>(map, odometry, params)) {}
Localizer::~Localizer() = default;

std::size_t Localizer::globalFixes() const { return impl_->fixes; }

LocalizationResult Localizer::process(const CObservationRadarScan& scan) {
  Impl& m = *impl_;
  LocalizationResult res;
  res.stamp = scan.refStampNs();

  // Algorithm 1 runs on a second thread while the odometry tracks the scan (both read it only).
  auto cloud_job = std::async(std::launch::async, [&] {
    const auto tc = Clock::now();
    auto c = extractPeakCloud(scan, m.params.peaks);
    return std::make_pair(std::move(c), msSince(tc));
  });
  auto t0 = Clock::now();
  const OdometryStep step = m.odometry.process(scan);
  res.timing.odometry = msSince(t0);
  auto [cloud, cloud_ms] = cloud_job.get();
  t0 = Clock::now();
  if (m.params.motion_compensation) compensateMotion(cloud, scan, step.velocity);
  res.timing.cloud = cloud_ms + msSince(t0);

  auto accept = [&](const TrackResult& tr, LocalizationStatus status) {
    m.pose = tr.icp.pose;
    m.have_pose = true;
    m.missed = 0;
    res.localised = true;
    res.pose = tr.icp.pose;
    res.covariance = tr.icp.covariance;
    res.fit_score = tr.icp.fit_score;
    res.inliers = tr.icp.inliers;
    res.status = status;
  };

  if (m.have_pose) {
    t0 = Clock::now();
    const mrpt::math::TPose2D predicted = compose(m.pose, step.motion);
    const TrackResult tr = m.tracker.track(cloud, predicted);
    res.timing.tracking = msSince(t0);
    if (tr.accepted) {
      accept(tr, LocalizationStatus::Tracking);
      return res;
    }
    res.fit_score = tr.icp.fit_score;
    res.inliers = tr.icp.inliers;
    m.pose = predicted;  // dead reckoning, never reported
    if (++m.missed > m.params.max_missed_scans) {
      m.have_pose = false;
      m.lost_scans = 0;
    }
    return res;
  }

  if (m.lost_scans++ % m.params.global_retry_interval != 0) return res;
  t0 = Clock::now();
  const GlobalFix fix = m.global.localize(cloud);
  if (fix.found) {
    // Confirm and refine the fix against the local submap (same tests as tracking).
    const TrackResult tr = m.tracker.track(cloud, fix.pose);
    if (tr.accepted) {
      accept(tr, LocalizationStatus::GlobalFix);
      ++m.fixes;
    }
  }
  res.timing.global = msSince(t0);
  return res;
}

}  // namespace radarslam
