// Localisation facade: odometry prediction, map tracking, global relocalisation; see
// reloc/localizer.h.
#include "radarslam/reloc/localizer.h"

#include <mrpt/poses/CPose2D.h>

#include <chrono>
#include <cmath>
#include <future>
#include <optional>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/frontend/odometry.h"
#include "radarslam/radar/motion_compensation.h"
#include "radarslam/reloc/map_motion.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, LocalizerParams& p) {
  yaml.get("motion_compensation", p.motion_compensation);
  yaml.get("max_missed_scans", p.max_missed_scans, Range::closed(0, 1000000.0));
  yaml.get("global_retry_interval", p.global_retry_interval, Range::closed(1, 1000000.0));
  yaml.get("map_sweep_period_s", p.map_sweep_period_s, Range::closed(0, 1000000.0));
  yaml.get("confirm_fixes", p.confirm_fixes, Range::closed(1, 100));
  yaml.get("confirm_distance_m", p.confirm_distance_m, Range::above(0, 1000));
  yaml.get("confirm_angle_deg", p.confirm_angle_deg, Range::above(0, 180));
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
  KeyframeMap compensated;  ///< only with map_sweep_period_s > 0
  const KeyframeMap& map;
  LocalizerParams params;
  RadarOdometry odometry;
  GlobalLocalizer global;
  MapTracker tracker;
  bool have_pose = false;  ///< pose is trusted or dead-reckoned from a trusted one
  mrpt::math::TPose2D pose;
  int missed = 0;       ///< rejected registrations in a row
  long lost_scans = 0;  ///< scans since global localisation became necessary
  std::size_t fixes = 0;
  std::optional<mrpt::math::TPose2D> pending;  ///< last unconfirmed fix, moved with the odometry
  int pending_count = 0;                       ///< consecutive agreeing fixes so far
  Impl(const KeyframeMap& map_in, const OdometryParams& op, const LocalizerParams& p)
      : compensated(p.map_sweep_period_s > 0 ? compensateMapMotion(map_in, p.map_sweep_period_s)
                                             : KeyframeMap{}),
        map(p.map_sweep_period_s > 0 ? compensated : map_in),
        params(p),
        odometry(op),
        global(map, p.global),
        tracker(map, p.tracker) {}
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

  if (m.pending) m.pending = compose(*m.pending, step.motion);
  if (m.lost_scans++ % m.params.global_retry_interval != 0) return res;
  t0 = Clock::now();
  const GlobalFix fix = m.global.localize(cloud);
  std::optional<TrackResult> refined;
  if (fix.found) {
    // Refine and check the fix against the local submap (same tests as tracking).
    TrackResult tr = m.tracker.track(cloud, fix.pose);
    if (tr.accepted) refined = std::move(tr);
  }
  if (!refined) {
    m.pending.reset();
    m.pending_count = 0;
  } else {
    const auto& p = refined->icp.pose;
    const bool agrees =
        m.pending && std::hypot(p.x - m.pending->x, p.y - m.pending->y) <= m.params.confirm_distance_m &&
        std::abs(std::remainder(p.phi - m.pending->phi, 2 * M_PI)) * 180 / M_PI <= m.params.confirm_angle_deg;
    m.pending_count = agrees ? m.pending_count + 1 : 1;
    m.pending = p;
    if (m.pending_count >= m.params.confirm_fixes) {
      accept(*refined, LocalizationStatus::GlobalFix);
      ++m.fixes;
      m.pending.reset();
      m.pending_count = 0;
    }
  }
  res.timing.global = msSince(t0);
  return res;
}

}  // namespace radarslam
