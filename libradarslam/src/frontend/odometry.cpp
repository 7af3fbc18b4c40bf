#include "radarslam/frontend/odometry.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "radarslam/core/log.h"
#include "radarslam/frontend/consistency_graph.h"
#include "radarslam/frontend/max_clique.h"
#include "radarslam/frontend/motion_prior_bound.h"
#include "radarslam/frontend/rigid_motion_choice.h"
#include "radarslam/frontend/structure_information.h"
#include "radarslam/frontend/svd_pose.h"

namespace radarslam {

const char* toString(TrackingStatus s) {
  switch (s) {
    case TrackingStatus::Initialised:
      return "initialised";
    case TrackingStatus::Tracking:
      return "tracking";
    case TrackingStatus::Lost:
      return "lost";
    case TrackingStatus::Recovered:
      return "recovered";
  }
  return "?";
}

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// a + t (a - b) per component (t = 0.5 with b = a's successor: the midpoint; t = -0.5:
/// extrapolation half a step beyond a away from b).
BodyVelocity blend(const BodyVelocity& a, const BodyVelocity& b, double t) {
  return {a.vx + t * (b.vx - a.vx), a.vy + t * (b.vy - a.vy), a.omega + t * (b.omega - a.omega)};
}

/// A keyframe point seen in the current scan: where (as imaged) and when (firing time offset).
struct Observation {
  int ref_index = -1;
  Eigen::Vector2d raw;
  double dt = 0.0;
};

/// One scan's features: as imaged (raw) and moved to the reference time (features.xy).
struct Frame {
  StampNs stamp = 0;
  mrpt::math::TPose2D pose;
  std::vector<cv::Point2f> pixels;  ///< keypoint positions in the Cartesian image
  AlignImage align;                 ///< the image prepared for patch alignment
  std::vector<Eigen::Vector2d> raw;
  std::vector<double> dt;  ///< firing time of each keypoint relative to the reference time, s
  FeatureSet features;
  /// Each keypoint's information shape from its image structure, in metres; computed when the frame
  /// becomes the keyframe (empty: not the keyframe, or isotropic).
  std::vector<Eigen::Matrix2d> structure;
  bool doppler = false;  ///< taken from a Doppler-compensated copy of the scan

  void compensate(const BodyVelocity& v, bool enabled) {
    features.xy.resize(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i)
      features.xy[i] = enabled ? compensatePoint(raw[i], dt[i], v) : raw[i];
  }
};

}  // namespace

struct RadarOdometry::Impl {
  explicit Impl(const OdometryParams& p)
      : params(p),
        converter(p.cartesian),
        extractor(p.keypoints),
        bound(p.matching, p.matching.keypoint_sigma_px * p.cartesian.m_per_px, p.matching.init_radius_m) {}

  OdometryParams params;
  PolarToCartesian converter;
  KeypointExtractor extractor;
  MotionPriorBound bound;  ///< search radius from the prediction's running error
  cv::Mat mask;            ///< excludes the near-range disk
  Trajectory trajectory;

  bool have_keyframe = false;
  Frame keyframe;
  StampNs last_stamp = 0;
  mrpt::math::TPose2D last_pose;
  BodyVelocity velocity;
  bool velocity_known = false;
  int lost_count = 0;
  int last_matches = 0;  ///< radius matches of the previous scan

  Frame makeFrame(const CObservationRadarScan& scan, StageTimes& times) {
    auto t0 = Clock::now();
    const cv::Mat image = converter.convert(scan);
    times.cartesian = msSince(t0);
    if (mask.size() != image.size()) {
      mask = cv::Mat(image.size(), CV_8UC1, cv::Scalar(255));
      const cv::Point2f c = converter.metresToPixel(0, 0);
      const int r = static_cast<int>(std::ceil(params.tracking.min_range_m / params.cartesian.m_per_px));
      cv::circle(mask, cv::Point(cvRound(c.x), cvRound(c.y)), r, cv::Scalar(0), cv::FILLED);
    }
    t0 = Clock::now();
    auto points = extractor.detect(image, mask);
    times.detect = msSince(t0);
    t0 = Clock::now();
    ImageKeypoints kps = extractor.describe(image, std::move(points));
    Frame f;
    f.stamp = scan.refStampNs();
    const AzimuthClock clock(scan);
    f.raw.reserve(kps.points.size());
    for (const auto& kp : kps.points) {
      f.pixels.push_back(kp.pt);
      const cv::Point2d m = converter.pixelToMetres(kp.pt.x, kp.pt.y);
      f.raw.emplace_back(m.x, m.y);
      f.dt.push_back(clock.offsetSeconds(std::atan2(m.y, m.x)));
    }
    f.features.descriptors = kps.descriptors;
    f.features.norm_type = kps.norm_type;
    times.describe = msSince(t0);
    t0 = Clock::now();
    if (params.patch_alignment.enabled) f.align = prepareAlignImage(image, params.patch_alignment);
    times.align_prep = msSince(t0);
    return f;
  }

  /// `f` becomes the keyframe: only the keyframe's points are weighed by their structure (eq. (4)
  /// and local BA), so their shapes are computed here, not for every scan.
  void setKeyframe(Frame&& f, StageTimes& times) {
    const auto t0 = Clock::now();
    if (params.refine.structure.enabled && !f.align.smooth.empty()) {
      // The patch whose alignment places the match (patch_radius_px) is the neighbourhood.
      const cv::Point2d o = converter.pixelToMetres(0, 0), ex = converter.pixelToMetres(1, 0),
                        ey = converter.pixelToMetres(0, 1);
      Eigen::Matrix2d pixel_to_metres;
      pixel_to_metres << ex.x - o.x, ey.x - o.x, ex.y - o.y, ey.y - o.y;
      f.structure.reserve(f.raw.size());
      for (std::size_t i = 0; i < f.raw.size(); ++i)
        f.structure.push_back(structureInformation(f.align.smooth, f.pixels[i],
                                                   params.patch_alignment.patch_radius_px, pixel_to_metres,
                                                   f.raw[i], params.refine.structure));
    }
    keyframe = std::move(f);
    times.align_prep += msSince(t0);
  }

  /// Outlier rejection (eq. (3) + maximum clique) and the SVD pose; returns the inlier set. With a
  /// prediction, the maximum clique is weighed against the second rigid motion of the matches.
  Correspondences selectInliers(Correspondences matches, OdometryStep& step, mrpt::math::TPose2D& svd_pose,
                                const MotionPrediction* prediction = nullptr) {
    auto t0 = Clock::now();
    const auto& o = params.outliers;
    if (static_cast<int>(matches.size()) > o.max_matches) {
      std::stable_sort(matches.begin(), matches.end(), [](const Correspondence& a, const Correspondence& b) {
        return a.descriptor_distance < b.descriptor_distance;
      });
      matches.resize(o.max_matches);
    }
    Correspondences clique;
    if (o.max_clique) {
      const DenseGraph g =
          buildConsistencyGraph(matches, o.delta_c_m,
                                o.consistency == "displacement" ? ConsistencyTest::DisplacementLength
                                                                : ConsistencyTest::PairwiseDistance);
      const CliqueResult c = maximumClique(g, o.max_clique_steps);
      step.clique_exact = c.exact;
      std::vector<int> rigid = c.vertices;
      if (prediction && o.second_motion) {
        RigidMotionChoice choice = chooseRigidMotion(matches, g, c.vertices, *prediction,
                                                     params.tracking.min_inliers, o.max_clique_steps);
        rigid = std::move(choice.vertices);
        step.second_motion = choice.second;
      }
      for (int v : rigid) clique.push_back(matches[v]);
    } else {
      clique = matches;
    }
    step.times.clique = msSince(t0);
    t0 = Clock::now();
    Correspondences inliers;
    if (const auto pose = fitPoseSvd(clique); pose && static_cast<int>(clique.size()) >= 2) {
      svd_pose = *pose;
      // Matches the clique missed but the SVD pose explains also join the refinement.
      const double gate2 = o.inlier_gate_m * o.inlier_gate_m;
      const double c = std::cos(pose->phi), s = std::sin(pose->phi);
      for (const auto& m : matches) {
        const Eigen::Vector2d pred(c * m.cur.x() - s * m.cur.y() + pose->x,
                                   s * m.cur.x() + c * m.cur.y() + pose->y);
        if ((pred - m.ref).squaredNorm() < gate2) inliers.push_back(m);
      }
      if (!o.max_clique) inliers = clique;  // ablation: no outlier rejection at all
    }
    step.times.svd = msSince(t0);
    return inliers;
  }

  /// Doppler compensation (radar/doppler_compensation.h) needs a tracked velocity: the last
  /// pair's twist, the best estimate before a scan is matched. The scan's azimuth rows are moved
  /// back by their offsets in a copy, before the Cartesian image is made (per azimuth: an
  /// alternating-chirp sensor shifts neighbouring azimuths in opposite directions, which cannot
  /// be undone per keypoint once the Cartesian image has blended them).
  bool dopplerOn() const { return params.doppler.enabled && params.doppler.beta_s != 0.0 && velocity_known; }
  bool dopplerReady(StampNs stamp) const {
    return dopplerOn() && have_keyframe &&
           toSeconds(stamp - last_stamp) <= params.tracking.max_prediction_gap_s;
  }
  const CObservationRadarScan& dopplerCompensated(const CObservationRadarScan& scan) {
    doppler_scan = scan;
    compensateDoppler(doppler_scan, velocity, params.doppler.beta_s);
    return doppler_scan;
  }
  CObservationRadarScan doppler_scan;  ///< scratch copy for dopplerCompensated()

  /// A frame about to become the keyframe is re-made from the compensated scan if it was not
  /// (the first frames, before a velocity was tracked): a scan is only matched against a keyframe
  /// in the same state, since a single-chirp offset alone looks like a shift of ~beta * v / 2.
  /// Its keypoints change, so it has no keyframe links.
  void makeDopplerKeyframe(Frame& f, const CObservationRadarScan& scan_in, const BodyVelocity& mc_velocity,
                           bool mc_enabled, OdometryStep& step) {
    if (f.doppler || !dopplerOn()) return;
    StageTimes scratch;
    Frame g = makeFrame(dopplerCompensated(scan_in), scratch);
    g.doppler = true;
    g.pose = f.pose;
    g.compensate(mc_velocity, mc_enabled);
    f = std::move(g);
    step.keyframe_observations.clear();  // measured in the image before Doppler compensation
  }

  OdometryStep process(const CObservationRadarScan& scan_in) {
    OdometryStep step;
    // Compensated only when the keyframe is too (see makeDopplerKeyframe).
    const bool doppler = dopplerReady(scan_in.refStampNs()) && keyframe.doppler;
    const CObservationRadarScan& scan = doppler ? dopplerCompensated(scan_in) : scan_in;
    Frame f = makeFrame(scan, step.times);
    f.doppler = doppler;
    step.stamp = f.stamp;
    step.keypoints = static_cast<int>(f.raw.size());
    const bool mc = params.tracking.motion_compensation;

    if (!have_keyframe) {
      f.compensate({}, mc);
      setKeyframe(std::move(f), step.times);
      have_keyframe = true;
      last_stamp = step.stamp;
      last_pose = step.pose = {0, 0, 0};
      step.status = TrackingStatus::Initialised;
      step.new_keyframe = true;
      step.keyframe_points = keyframe.features.xy;
      trajectory.push_back({step.stamp, step.pose});
      return step;
    }

    const double dt = toSeconds(step.stamp - last_stamp);
    // A gap in the data (a timestamp jump, many dropped scans): constant velocity across it would
    // extrapolate far off. Re-initialise instead: no predicted motion, wide search radius, and the
    // velocity is re-estimated from the next pair (one spanning the gap says nothing about it).
    const bool gap = dt > params.tracking.max_prediction_gap_s;
    const mrpt::math::TPose2D predicted_delta =
        velocity_known && !gap ? twistToPose(velocity, dt) : mrpt::math::TPose2D();
    const mrpt::math::TPose2D kf_to_last = last_pose - keyframe.pose;  // T_k_prev
    const mrpt::math::TPose2D prior = kf_to_last + predicted_delta;
    // Without a velocity (start, data gap) the paper's wide initial radius; otherwise the bound
    // from the prediction's running error, widened with the frames lost since the last estimate
    // (adaptive_radius off: the fixed radius, and the wide one after a loss).
    const bool adaptive = params.matching.adaptive_radius;
    const bool wide = !velocity_known || gap || (!adaptive && lost_count > 0);
    const SearchRadius radius =
        wide ? SearchRadius::fixed(params.matching.init_radius_m) : bound.radius(lost_count);

    // A road vehicle cannot change its velocity by more than a_max dt in one scan, so its
    // translation cannot leave the constant-velocity prediction by more than a_max dt^2 (per scan
    // since the last estimate) plus the estimation noise `noise_m`. An estimate beyond that is not
    // the motion (keypoints of a featureless wall matched one step along it, vehicle-fixed clutter
    // matched at zero motion).
    const double accel_reach = params.tracking.max_acceleration_mps2 * dt * dt * (1 + lost_count);
    const double keypoint_sigma_m = params.matching.keypoint_sigma_px * params.cartesian.m_per_px;
    auto physicallyPossible = [&](const mrpt::math::TPose2D& estimate, double noise_m) {
      const mrpt::math::TPose2D deviation = estimate - prior;
      return std::hypot(deviation.x, deviation.y) <= accel_reach + noise_m;
    };

    BodyVelocity v = velocity_known ? velocity : BodyVelocity{};
    BodyVelocity cur_compensation = v;
    f.compensate(v, mc);
    auto t0 = Clock::now();
    step.predicted_motion = predicted_delta;
    step.search_radius = radius;
    Correspondences matches =
        matchWithinRadius(f.features, keyframe.features, prior, radius, params.matching);
    step.times.match = msSince(t0);
    step.matches = static_cast<int>(matches.size());

    mrpt::math::TPose2D svd_pose;
    // The prediction the rigid sets are weighed against: only once the bound has measured the
    // prediction's error, and not when the wide radius is used (start, data gap, loss with the
    // fixed radius: no velocity to trust).
    const MotionPrediction prediction{prior, bound.sigmaTranslation(), radius.fixed_m, keypoint_sigma_m};
    const bool predicted = !wide && prediction.sigma_m > 0;
    Correspondences inliers = selectInliers(matches, step, svd_pose, predicted ? &prediction : nullptr);
    step.inliers = static_cast<int>(inliers.size());
    if (adaptive && !wide &&
        (step.inliers < params.tracking.min_inliers || 2 * step.matches < last_matches)) {
      // The motion left the model's bound (a turn entered harder than anything seen so far: too
      // few inliers, or the matches collapsed against the previous scan's): one more try with the
      // paper's wide radius; the larger inlier set wins.
      t0 = Clock::now();
      Correspondences wide_matches = matchWithinRadius(f.features, keyframe.features, prior,
                                                       params.matching.init_radius_m, params.matching);
      step.times.match += msSince(t0);
      OdometryStep retry;
      mrpt::math::TPose2D wide_pose;
      Correspondences wide_inliers = selectInliers(wide_matches, retry, wide_pose);
      step.times.clique += retry.times.clique;
      step.times.svd += retry.times.svd;
      if (wide_inliers.size() > inliers.size() && physicallyPossible(wide_pose, radius.fixed_m)) {
        matches = std::move(wide_matches);
        inliers = std::move(wide_inliers);
        svd_pose = wide_pose;
        step.clique_exact = retry.clique_exact;
        step.second_motion = retry.second_motion;  // the wide re-match weighs no prediction
        step.matches = static_cast<int>(matches.size());
        step.inliers = static_cast<int>(inliers.size());
        step.widened = true;
        step.search_radius = SearchRadius::fixed(params.matching.init_radius_m);
      }
    }
    last_matches = step.matches;

    bool ok = step.inliers >= params.tracking.min_inliers;
    mrpt::math::TPose2D T = svd_pose;  // T_k_t
    t0 = Clock::now();
    const bool kf_is_last = keyframe.stamp == last_stamp;
    const bool accel = params.tracking.acceleration_aware && velocity_known;
    const AzimuthClock clock(scan);
    auto observe = [&](int ref_index, cv::Point2f pixel) {
      const cv::Point2d xy = converter.pixelToMetres(pixel.x, pixel.y);
      return Observation{ref_index, {xy.x, xy.y}, clock.offsetSeconds(std::atan2(xy.y, xy.x))};
    };
    // Motion compensation (ours, not the paper's), re-done with each refined estimate. Each scan is
    // compensated with its velocity at its own reference time: the keyframe (when it is the
    // previous scan) with the mean of the pair velocities before and after it, the current scan
    // with the latest pair velocity extrapolated by the change since the previous pair.
    auto currentVelocity = [&](const BodyVelocity& pair) {
      return accel ? blend(pair, velocity, -0.5) : pair;
    };
    // The motion model as a prior on eq. (4) (ours, pose_refiner.h): the constant-velocity
    // prediction with its measured error's covariance, grown like the search radius with the
    // frames lost since the last estimate. Not when the model has no measured error yet (start,
    // data gap, wide radius) or the scan was re-matched wide (the motion just left the model).
    PosePrior motion_prior{prior, bound.covariance() * (1.0 + lost_count)};
    const bool use_prior = params.refine.motion_prior && predicted && !step.widened &&
                           bound.samples() >= params.matching.adaptive_min_samples;
    auto refine = [&](const std::vector<Observation>& obs) {  // eq. (4), with compensation passes
      const int passes = mc ? std::max(1, params.tracking.compensation_passes) : 1;
      for (int pass = 0; pass < passes; ++pass) {
        if (pass > 0 && kf_is_last) keyframe.compensate(velocity_known ? blend(velocity, v, 0.5) : v, mc);
        Correspondences c(obs.size());
        std::vector<Eigen::Matrix2d> shapes;
        if (!keyframe.structure.empty()) shapes.reserve(obs.size());
        const BodyVelocity vc = currentVelocity(v);
        for (std::size_t i = 0; i < obs.size(); ++i) {
          c[i].cur = mc ? compensatePoint(obs[i].raw, obs[i].dt, vc) : obs[i].raw;
          c[i].ref = keyframe.features.xy[obs[i].ref_index];
          if (!keyframe.structure.empty()) shapes.push_back(keyframe.structure[obs[i].ref_index]);
        }
        const RefineResult refined =
            refinePose(c, T, params.refine, shapes, use_prior ? &motion_prior : nullptr);
        T = refined.pose;
        step.prior_chi2 = refined.prior_chi2;
        step.prior_applied = refined.prior_applied;
        v = twistFromDelta((keyframe.pose + T) - last_pose, dt);
      }
    };
    t0 = Clock::now();
    // The observations the pose is refined with: the descriptor inliers first (in order), then
    // the tracked keyframe points.
    std::vector<Observation> obs;
    if (ok) {
      // Descriptor inliers, each moved to where the keyframe's patch really lies (sub-pixel).
      std::vector<char> observed(keyframe.raw.size(), 0);
      for (const auto& m : inliers) {
        cv::Point2f px = f.pixels[m.cur_index];
        if (params.patch_alignment.enabled) {
          const auto a =
              alignPatch(keyframe.align, keyframe.pixels[m.ref_index], f.align, px, params.patch_alignment);
          if (a.ok) px = a.position;
        }
        obs.push_back(observe(m.ref_index, px));
        observed[m.ref_index] = 1;
      }
      refine(obs);
      if (params.patch_alignment.enabled && params.patch_alignment.track_keyframe_points) {
        // Every other keyframe point (a map point of eq. (4)) is looked for where the estimate
        // puts it in this image, and kept if its patch aligns and it agrees with the estimate.
        const mrpt::math::TPose2D Tinv = mrpt::math::TPose2D(0, 0, 0) - T;
        const BodyVelocity vc = currentVelocity(v);
        const double gate2 = params.patch_alignment.track_gate_m * params.patch_alignment.track_gate_m;
        PatchAlignParams pa = params.patch_alignment;
        pa.search_radius_px = pa.track_search_radius_px;
        const std::size_t before = obs.size();
        for (std::size_t j = 0; j < keyframe.raw.size(); ++j) {
          if (observed[j]) continue;
          const auto q = Tinv.composePoint({keyframe.features.xy[j].x(), keyframe.features.xy[j].y()});
          const Eigen::Vector2d raw =
              mc ? decompensatePoint({q.x, q.y}, clock.offsetSeconds(std::atan2(q.y, q.x)), vc)
                 : Eigen::Vector2d(q.x, q.y);
          const auto a = alignPatch(keyframe.align, keyframe.pixels[j], f.align,
                                    converter.metresToPixel(raw.x(), raw.y()), pa);
          if (!a.ok) continue;
          Observation o = observe(static_cast<int>(j), a.position);
          const Eigen::Vector2d cur = mc ? compensatePoint(o.raw, o.dt, vc) : o.raw;
          const auto pred = T.composePoint({cur.x(), cur.y()});
          if ((Eigen::Vector2d(pred.x, pred.y) - keyframe.features.xy[j]).squaredNorm() < gate2)
            obs.push_back(o);
        }
        if (obs.size() > before) refine(obs);
      }
      step.inliers = static_cast<int>(obs.size());
      const double speed = std::hypot(v.vx, v.vy);
      if (!(dt > 0) || speed > params.tracking.max_speed_mps) ok = false;
      // The estimate's own noise: k sigma of the difference of two poses each averaged over the
      // observations (keypoint noise / sqrt(n)), not the search radius (which bounds one keypoint).
      const double estimate_noise_m = params.matching.radius_sigmas * std::sqrt(2.0) * keypoint_sigma_m /
                                      std::sqrt(std::max(1.0, static_cast<double>(obs.size())));
      if (ok && velocity_known && !gap && !physicallyPossible(T, estimate_noise_m)) {
        ok = false;
        step.implausible = true;
        logger().logFmt(mrpt::system::LVL_WARN,
                        "odometry: tracking lost at %.3f s (the estimate leaves the constant-velocity "
                        "prediction by more than %.2f m: no road vehicle accelerates that hard)",
                        toSeconds(step.stamp), accel_reach + estimate_noise_m);
      }
    }
    cur_compensation = currentVelocity(v);
    step.times.refine = msSince(t0);

    if (ok) {
      if (velocity_known && !gap && lost_count == 0)
        bound.addDeviation(predicted_delta, (keyframe.pose + T) - last_pose);
      step.status = lost_count > 0 ? TrackingStatus::Recovered : TrackingStatus::Tracking;
      lost_count = 0;
      step.pose = keyframe.pose + T;  // eq. (2): C_t = C_k T_tk^-1, with T = T_tk^-1
      velocity = v;
      velocity_known = !gap;
      f.compensate(cur_compensation, mc);
      if (needNewKeyframe(params.keyframes, T, step.inliers)) {
        // Observations for local mapping: those the final estimate still explains.
        const double gate2 = params.outliers.inlier_gate_m * params.outliers.inlier_gate_m;
        const double c = std::cos(T.phi), s = std::sin(T.phi);
        for (std::size_t i = 0; i < obs.size(); ++i) {
          const Eigen::Vector2d q =
              mc ? compensatePoint(obs[i].raw, obs[i].dt, cur_compensation) : obs[i].raw;
          const Eigen::Vector2d pred(c * q.x() - s * q.y() + T.x, s * q.x() + c * q.y() + T.y);
          if ((pred - keyframe.features.xy[obs[i].ref_index]).squaredNorm() < gate2) {
            KeyframeObservation o{obs[i].ref_index, i < inliers.size() ? inliers[i].cur_index : -1, q};
            if (!keyframe.structure.empty()) {  // the same patch, turned into the new keyframe's frame
              Eigen::Matrix2d r;
              r << c, -s, s, c;
              o.information = r.transpose() * keyframe.structure[obs[i].ref_index] * r;
            }
            step.keyframe_observations.push_back(o);
          }
        }
        f.pose = step.pose;
        makeDopplerKeyframe(f, scan_in, cur_compensation, mc, step);
        setKeyframe(std::move(f), step.times);
        step.new_keyframe = true;
        step.keyframe_points = keyframe.features.xy;
        step.keyframe_structure = keyframe.structure;
      }
    } else {
      // Tracking loss: constant-velocity prediction, re-initialise on this scan.
      step.status = TrackingStatus::Lost;
      ++lost_count;
      step.pose = last_pose + predicted_delta;
      // Re-initialise on this scan, unless it is too poor to track against (e.g. blank) and the
      // old keyframe is recent: then the next scan is matched against the old keyframe.
      const bool poor = step.keypoints < 2 * params.tracking.min_inliers;
      if (!poor || lost_count > params.tracking.keep_keyframe_when_lost) {
        f.pose = step.pose;
        f.compensate(velocity, mc && velocity_known);
        makeDopplerKeyframe(f, scan_in, velocity, mc && velocity_known, step);
        setKeyframe(std::move(f), step.times);
        step.new_keyframe = true;
        step.keyframe_points = keyframe.features.xy;
        step.keyframe_structure = keyframe.structure;
      }
      if (!step.implausible)  // (an implausible estimate was reported where it was found)
        logger().logFmt(mrpt::system::LVL_WARN, "odometry: tracking lost at %.3f s (%d matches, %d inliers)",
                        toSeconds(step.stamp), step.matches, step.inliers);
    }
    step.motion = step.pose - last_pose;
    step.velocity = velocity;
    last_pose = step.pose;
    last_stamp = step.stamp;
    trajectory.push_back({step.stamp, step.pose});
    return step;
  }
};

RadarOdometry::RadarOdometry(const OdometryParams& params) : impl_(std::make_unique<Impl>(params)) {}
RadarOdometry::~RadarOdometry() = default;
OdometryStep RadarOdometry::process(const CObservationRadarScan& scan) { return impl_->process(scan); }
const Trajectory& RadarOdometry::trajectory() const { return impl_->trajectory; }
const OdometryParams& RadarOdometry::params() const { return impl_->params; }

}  // namespace radarslam
