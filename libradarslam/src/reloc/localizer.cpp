// Localisation facade: odometry prediction, map tracking, global relocalisation; see
// reloc/localizer.h.
#include "radarslam/reloc/localizer.h"

#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <optional>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/frontend/odometry.h"
#include "radarslam/map/keyframe_search.h"
#include "radarslam/radar/motion_compensation.h"
#include "radarslam/reloc/fix_hypotheses.h"
#include "radarslam/reloc/map_connectivity.h"
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
  yaml.get("odometry_adaptive_radius", p.odometry_adaptive_radius);
  yaml.get("gate_fixes_with_odometry", p.gate_fixes_with_odometry);
  yaml.get("degraded_fixes", p.degraded_fixes);
  yaml.get("resolve_contested_fixes", p.resolve_contested_fixes);
  yaml.get("resolve_contested_fixes_after_loss", p.resolve_contested_fixes_after_loss);
  loadParams(yaml.section("peak_cloud"), p.peaks);
  loadParams(yaml.section("global"), p.global);
  loadParams(yaml.section("tracker"), p.tracker);
  loadParams(yaml.section("integrity"), p.integrity);
}

const char* toString(LocalizationStatus s) {
  switch (s) {
    case LocalizationStatus::GlobalFix:
      return "global_fix";
    case LocalizationStatus::Tracking:
      return "tracking";
    case LocalizationStatus::Degraded:
      return "degraded";
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
/// Covariance of keyframe b's pose relative to keyframe a's, in the map frame, with the odometry
/// noise model compounded along the shortest path between them through the map's graph: its
/// odometry links and the revisits the map merged (reloc/map_connectivity.h; as SLAM's
/// graphPathLength). Two places a revisit tied together are as certain relative to each other as
/// the short path says, not as the whole drive between them (the keyframe order, used only when no
/// path joins them).
Eigen::Matrix3d mapChainCovariance(const KeyframeMap& map, const MapConnectivity& graph, long a, long b,
                                   const IntegrityParams& ip) {
  if (a < 0 || b < 0 || a == b) return Eigen::Matrix3d::Zero();
  std::vector<std::size_t> path = graph.path(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
  if (path.empty())
    for (long k = std::min(a, b); k <= std::max(a, b); ++k) path.push_back(static_cast<std::size_t>(k));
  return pathCovariance(map, path, ip);
}
/// The tracker's checks (g), (h) bound their rivals as the integrity checks bound an innovation.
MapTrackerParams withRivalBound(MapTrackerParams t, double chi2_threshold) {
  t.rival_chi2 = chi2_threshold;
  return t;
}
}  // namespace

bool compensatesMap(const KeyframeMap& map, const LocalizerParams& params) {
  return params.map_sweep_period_s > 0 && !map.meta.clouds_motion_compensated;
}

struct Localizer::Impl {
  std::optional<KeyframeMap> compensated;  ///< only for a map of raw clouds (compensatesMap)
  const KeyframeMap& map;
  LocalizerParams params;
  double chi2_threshold;  ///< chi^2(3) quantile of integrity.chi2_probability
  RadarOdometry odometry;
  GlobalLocalizer global;
  MapConnectivity graph;  ///< the map's keyframe graph: the prior gate's path covariance
  MapTracker tracker;
  bool have_pose = false;  ///< pose is trusted or dead-reckoned from a trusted one
  mrpt::math::TPose2D pose;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();  ///< of pose
  FitMonitor fits;
  MotionWindow window;
  int missed = 0;       ///< rejected registrations (failed checks) in a row
  long lost_scans = 0;  ///< scans since global localisation became necessary
  std::size_t fixes = 0;
  std::optional<mrpt::math::TPose2D> pending;  ///< last unconfirmed fix, moved with the odometry
  int pending_count = 0;                       ///< consecutive agreeing fixes so far
  /// While lost: the last pose dead-reckoned on with the odometry and its growing covariance, as
  /// long as the odometry keeps tracking without a data gap (no prior after a kidnap, a gap or a
  /// lost odometry scan; none before the first fix). Global fixes must agree with it (chi^2).
  struct Prior {
    mrpt::math::TPose2D pose;
    Eigen::Matrix3d cov;
    long anchor = -1;  ///< the map keyframe of the last trusted registration
  };
  long trusted_keyframe = -1;  ///< nearest map keyframe of the last tracking / global_fix pose
  long anchor = -1;            ///< keyframe of the map copy being tracked (MapTracker::track)
  std::optional<Prior> prior;
  FixHypotheses hypotheses;  ///< while lost: contested places followed over the scans
  StampNs last_stamp = 0;
  Impl(const KeyframeMap& map_in, const OdometryParams& op, const LocalizerParams& p)
      : compensated(compensatesMap(map_in, p)
                        ? std::optional<KeyframeMap>(compensateMapMotion(map_in, p.map_sweep_period_s))
                        : std::nullopt),
        map(compensated ? *compensated : map_in),
        params(p),
        chi2_threshold(chi2Quantile3(p.integrity.chi2_probability)),
        odometry([&] {
          OdometryParams o = op;
          o.matching.adaptive_radius = p.odometry_adaptive_radius;
          return o;
        }()),
        global(map, p.global),
        graph(map),
        tracker(map, withRivalBound(p.tracker, chi2_threshold)),
        fits(p.integrity),
        window(p.integrity),
        hypotheses(tracker, map, chi2_threshold) {}
  void loseTrack(const mrpt::math::TPose2D& last, const Eigen::Matrix3d& last_cov) {
    if (params.gate_fixes_with_odometry) prior = Prior{last, last_cov, trusted_keyframe};
    loseTrack();
  }
  void loseTrack() {
    have_pose = false;
    anchor = -1;
    lost_scans = 0;
    fits.clear();
    window.clear();
  }
};

Localizer::Localizer(const KeyframeMap& map, const OdometryParams& odometry, const LocalizerParams& params)
    : impl_(std::make_unique<Impl>(map, odometry, params)) {}
Localizer::~Localizer() = default;

std::size_t Localizer::globalFixes() const { return impl_->fixes; }
const IcpParams& Localizer::registrationModel() const { return impl_->tracker.params().icp; }

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
  const bool data_gap = m.last_stamp != 0 && toSeconds(res.stamp - m.last_stamp) >
                                                 m.odometry.params().tracking.max_prediction_gap_s;
  m.last_stamp = res.stamp;
  auto [cloud, cloud_ms] = cloud_job.get();
  t0 = Clock::now();
  if (m.params.motion_compensation) compensateMotion(cloud, scan, step.velocity);
  res.timing.cloud = cloud_ms + msSince(t0);

  auto report = [&](const mrpt::math::TPose2D& pose, const Eigen::Matrix3d& cov, LocalizationStatus status,
                    long keyframe = -1) {
    m.pose = pose;
    m.cov = cov;
    m.have_pose = true;
    res.localised = true;
    res.pose = pose;
    res.covariance = cov;
    res.status = status;
    res.keyframe = keyframe >= 0 ? keyframe : nearestKeyframe(m.map, pose.x, pose.y);
    if (status == LocalizationStatus::Tracking || status == LocalizationStatus::GlobalFix)
      m.trusted_keyframe = res.keyframe;
  };
  auto accept = [&](const TrackResult& tr, LocalizationStatus status) {
    m.missed = 0;
    m.anchor = tr.anchor;
    report(tr.icp.pose, tr.icp.covariance, status, tr.anchor);
    res.fit_score = tr.icp.fit_score;
    res.inliers = tr.icp.inliers;
  };
  const IntegrityParams& ip = m.params.integrity;

  if (m.have_pose && !ip.enabled) {  // the tracker's own tests only (before issue #14)
    t0 = Clock::now();
    const mrpt::math::TPose2D predicted = compose(m.pose, step.motion);
    const TrackResult tr = m.tracker.track(cloud, predicted, m.anchor);
    res.timing.tracking = msSince(t0);
    if (tr.accepted) {
      accept(tr, LocalizationStatus::Tracking);
      return res;
    }
    res.fit_score = tr.icp.fit_score;
    res.inliers = tr.icp.inliers;
    m.pose = predicted;  // dead reckoning, never reported
    if (++m.missed > m.params.max_missed_scans) m.loseTrack();
    return res;
  }

  if (m.have_pose) {
    t0 = Clock::now();
    // Prediction with the odometry noise model; a lost/re-initialised odometry gives no motion
    // information (a huge variance), so the map registration alone decides.
    const bool odo_ok = step.status == TrackingStatus::Tracking;
    const Eigen::Matrix3d odo_cov = odo_ok ? odometryCovariance(step.motion, ip)
                                           : Eigen::Vector3d(1e4, 1e4, 10.0).asDiagonal().toDenseMatrix();
    const mrpt::math::TPose2D predicted = compose(m.pose, step.motion);
    const Eigen::Matrix3d predicted_cov = composeCovariance(m.pose, m.cov, step.motion, odo_cov);
    m.window.addMotion(step.motion, odo_cov);
    const TrackResult tr = m.tracker.track(cloud, predicted, m.anchor, &predicted_cov);
    if (!tr.accepted)
      logger().logFmt(mrpt::system::LVL_DEBUG, "tracking: %s%s", tr.degenerate ? "degenerate: " : "",
                      tr.reason.c_str());
    res.fit_score = tr.icp.fit_score;
    res.inliers = tr.icp.inliers;
    const IcpResult& r = tr.icp;
    // The checks, in order; the first failure is reported in res.check.
    if (!tr.accepted && !tr.degenerate) {
      res.check = "registration";  // tr.reason has the details
    } else if (mahalanobis2(poseDifference(predicted, r.pose), predicted_cov + r.covariance) >
               m.chi2_threshold) {
      res.check = "odometry";
    } else if (m.fits.drop(r.fit_score)) {
      res.check = "fit";
    } else if (m.window.test(r.pose, r.covariance) > m.chi2_threshold) {
      res.check = "window";
    }
    if (res.check.empty()) {
      m.missed = 0;
      m.fits.add(r.fit_score);
      if (tr.degenerate || xyCondition(r.covariance) > ip.max_condition) {
        // A weak direction: the odometry prediction fills it.
        mrpt::math::TPose2D fused;
        Eigen::Matrix3d fused_cov;
        fusePoses(predicted, predicted_cov, r.pose, r.covariance, fused, fused_cov);
        report(fused, fused_cov, LocalizationStatus::Degraded, tr.anchor);
        res.check = tr.reacquisition_ambiguous ? "reacquisition" : "degenerate";
      } else if (tr.map_inconsistent) {
        // Check (i): the map disagrees with itself around the anchor. The client relates the pose
        // to the anchor, so where the scan's alignment against the anchor keyframe's cloud differs
        // that one is reported; either way as uncertain as the map disagrees.
        const IcpResult& a = tr.anchor_alignment_differs ? tr.anchor_alignment : r;
        report(a.pose, a.covariance + tr.map_disagreement, LocalizationStatus::Degraded, tr.anchor);
        res.check = "map";
      } else if (const MapCoverage cover = mapCoverage(m.map, r.pose, ip); cover.outside) {
        // Check (f): outside the mapped path; relative to the map as uncertain as the odometry
        // over the distance from the nearest keyframe.
        report(r.pose, r.covariance + cover.extra_cov, LocalizationStatus::Degraded, tr.anchor);
        res.check = "outside";
      } else {
        report(r.pose, r.covariance, LocalizationStatus::Tracking, tr.anchor);
      }
      m.anchor = tr.anchor;
      if (tr.ambiguous) {
        res.ambiguous = true;
        if (res.check.empty()) res.check = "ambiguous";
      }
      m.window.addPose(true, res.pose, res.covariance);
    } else {
      // Dead reckoning with the odometry, reported as degraded while its covariance stays bounded.
      m.window.addPose(false, predicted, predicted_cov);
      if (++m.missed > ip.max_failures || position3Sigma(predicted_cov) > ip.max_position_3sigma_m) {
        m.loseTrack(predicted, predicted_cov);
      } else {
        report(predicted, predicted_cov, LocalizationStatus::Degraded);
      }
    }
    res.timing.tracking = msSince(t0);
    return res;
  }

  if (m.pending) m.pending = compose(*m.pending, step.motion);
  // Dead reckoning (the prior, the contested hypotheses) goes on only through scans the odometry
  // tracked (a lost or re-initialised odometry, or a gap in the data, says nothing about the
  // motion: a kidnapping looks like that).
  const bool odometry_continuous = step.status == TrackingStatus::Tracking && !data_gap;
  if (m.prior) {
    if (!odometry_continuous) {
      m.prior.reset();
    } else {
      m.prior->cov =
          composeCovariance(m.prior->pose, m.prior->cov, step.motion, odometryCovariance(step.motion, ip));
      m.prior->pose = compose(m.prior->pose, step.motion);
    }
  }
  // A fix the dead-reckoned pose rules out (chi^2 of the difference under both covariances) is a
  // look-alike place, however well it verifies (docs/localization.md, "Global fixes").
  // The map is not exact either: where the fix lies in another part of the map than the prior's
  // anchor, the two parts' relative pose is uncertain as the odometry that built them.
  const FixHypotheses::Gate prior_allows = [&](const TrackResult& tr) {
    return !m.prior ||
           mahalanobis2(poseDifference(m.prior->pose, tr.icp.pose),
                        m.prior->cov +
                            mapChainCovariance(m.map, m.graph, m.prior->anchor,
                                               nearestKeyframe(m.map, tr.icp.pose.x, tr.icp.pose.y), ip) +
                            tr.icp.covariance) <= m.chi2_threshold;
  };
  t0 = Clock::now();
  if (!m.hypotheses.empty()) {
    if (odometry_continuous)
      m.hypotheses.advance(cloud, step.motion, odometryCovariance(step.motion, ip), prior_allows);
    else
      m.hypotheses.clear();
  }
  const bool search = m.lost_scans++ % m.params.global_retry_interval == 0;
  if (!search && m.hypotheses.empty()) return res;
  const GlobalFix fix = search ? m.global.localize(cloud) : GlobalFix{};
  std::optional<TrackResult> candidate;
  if (fix.found) {
    // Refine and check the fix against the local submap (same tests as tracking).
    candidate = m.tracker.track(cloud, fix.pose, static_cast<long>(fix.keyframe));
  } else if ((m.params.resolve_contested_fixes || (m.params.resolve_contested_fixes_after_loss && m.prior)) &&
             !fix.contested.empty()) {
    // Places refused only as ambiguous become hypotheses, told apart over the next scans; while
    // they live, each search that points at one again supports it.
    if (m.hypotheses.empty())
      m.hypotheses.seed(cloud, fix.contested, prior_allows);
    else
      m.hypotheses.support(fix.contested);
  }
  if (!m.hypotheses.empty())
    logger().logFmt(mrpt::system::LVL_DEBUG,
                    "global: %zu contested places, %zu hypotheses (%zu registrations)", fix.contested.size(),
                    m.hypotheses.size(), m.hypotheses.registrations());
  // A fix: tracking goes on from it (a degenerate one as degraded_fixes says, its wide covariance
  // starting check (h)).
  auto fixed = [&](const TrackResult& tr) {
    if (tr.accepted) {
      accept(tr, LocalizationStatus::GlobalFix);
    } else {
      accept(tr, LocalizationStatus::Degraded);
      res.check = "degenerate_fix";
    }
    m.fits.clear();
    m.window.clear();
    m.window.addMotion(step.motion, Eigen::Matrix3d::Zero());
    m.window.addPose(true, res.pose, res.covariance);
    ++m.fixes;
    m.prior.reset();
    m.pending.reset();
    m.pending_count = 0;
    m.hypotheses.clear();
  };
  std::optional<TrackResult> refined;
  if (candidate) {
    TrackResult& tr = *candidate;
    // A refinement that failed only the weak-direction tests (degenerate) still holds the place the
    // verifier found unique; it can become a degraded fix with its inflated covariance.
    const bool usable = tr.accepted || (m.params.degraded_fixes && tr.degenerate);
    if (usable && !prior_allows(tr)) {
      res.check = "prior";
    } else if (usable) {
      refined = std::move(tr);
    }
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
    if (m.pending_count >= m.params.confirm_fixes) fixed(*refined);
  }
  // The one contested hypothesis left, registered in confirm_fixes consecutive scans: every rival
  // ruled out by the map along the drive (reloc/fix_hypotheses.h).
  // A verified fix of this scan elsewhere contests it: wait.
  if (!m.have_pose)
    if (const FixHypothesis* h = m.hypotheses.unique(m.params.confirm_fixes);
        h && (h->last.accepted || m.params.degraded_fixes) &&
        (!refined || !differentAlignments(refined->icp, h->last.icp, m.params.tracker.icp))) {
      const TrackResult tr = h->last;  // a copy: fixed() clears the hypotheses
      fixed(tr);
      res.contested_fix = true;
    }
  res.timing.global = msSince(t0);
  return res;
}

}  // namespace radarslam
