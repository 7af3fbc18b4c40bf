#include "radarslam/slam/radar_slam.h"

#include <chrono>
#include <map>
#include <stdexcept>
#include <thread>

#include "graph_optimiser.h"
#include "local_mapper.h"
#include "loop_closer.h"
#include "work_queue.h"

namespace radarslam {

using namespace slam_detail;

namespace {
/// A processed scan, anchored to the keyframe it was tracked from.
struct ScanAnchor {
  StampNs stamp = 0;
  std::uint64_t keyframe = 0;
  TPose2D odom_pose;
};
constexpr std::size_t kQueueCapacity = 8;  // keyframe jobs per queue (until described, each holds a scan)
}  // namespace

struct RadarSlam::Impl {
  explicit Impl(const SlamParams& p)
      : params(p), odometry(p.odometry), mapper(state, params), closer(state, params) {
    if (params.threads >= 2) {
      // Tracking -> describe (peak cloud, M2DP) -> local mapping -> loop closing, each stage in its
      // own thread: describing needs only the job, so it overlaps the previous keyframe's BA.
      describe_thread = std::thread([this] {
        while (auto job = describe_queue.pop()) {
          mapper.describe(*job);
          mapping_queue.push(std::move(*job));
        }
        mapping_queue.close();
      });
      mapping_thread = std::thread([this] {
        while (auto job = mapping_queue.pop()) {
          mapper.insert(*job);
          loop_queue.push(job->id);
        }
        loop_queue.close();
      });
      loop_thread = std::thread([this] {
        while (auto id = loop_queue.pop()) closer.process(*id);
      });
    }
  }
  ~Impl() { stopThreads(); }

  void stopThreads() {
    describe_queue.close();
    if (describe_thread.joinable()) describe_thread.join();
    mapping_queue.close();
    if (mapping_thread.joinable()) mapping_thread.join();
    loop_queue.close();
    if (loop_thread.joinable()) loop_thread.join();
  }

  SlamParams params;
  SlamState state;
  RadarOdometry odometry;
  LocalMapper mapper;
  LoopCloser closer;
  WorkQueue<KeyframeJob> describe_queue{kQueueCapacity}, mapping_queue{kQueueCapacity};
  WorkQueue<std::uint64_t> loop_queue{kQueueCapacity};
  std::thread describe_thread, mapping_thread, loop_thread;

  std::vector<ScanAnchor> anchors;
  std::uint64_t next_keyframe = 0;
  TPose2D last_odom;
  double travelled = 0;
  MapSensorGeometry sensor;
  bool finished = false;

  /// Map-frame pose of a scan: its keyframe's estimate (or the newest inserted one's, while local
  /// mapping has not caught up) composed with the tracked motion since. Needs the state lock.
  TPose2D mapPose(const ScanAnchor& a) const {
    const auto& kfs = state.keyframes;
    if (kfs.empty()) return a.odom_pose;
    const SlamKeyframe& kf = a.keyframe < kfs.size() ? kfs[a.keyframe] : kfs.back();
    return compose(kf.pose, between(kf.odom_pose, a.odom_pose));
  }

  void extend(const KeyframeMap& base) {
    if (!anchors.empty() || !state.keyframes.empty())
      throw std::logic_error("RadarSlam::extend after process()");
    if (base.keyframes.empty()) throw std::invalid_argument("RadarSlam::extend: the map has no keyframe");
    if (!base.meta.clouds_motion_compensated)  // the new session's clouds would not match them
      throw std::invalid_argument(
          "the map's keyframe clouds are raw sweeps (clouds_motion_compensated: false, a map-synth map); "
          "--extend needs a map built by radarslam map");
    std::map<std::uint64_t, std::uint64_t> index;  // map keyframe id -> state index
    double travelled_m = 0;
    for (const auto& k : base.keyframes) {
      SlamKeyframe kf;
      kf.id = state.keyframes.size();
      index[k.id] = kf.id;
      kf.stamp = k.stamp_ns;
      kf.pose = kf.odom_pose = k.pose;
      kf.session_start = kf.id == 0;
      if (kf.id > 0) {
        const TPose2D& prev = state.keyframes.back().pose;
        kf.odom_edge = between(prev, k.pose);
        travelled_m += std::hypot(kf.odom_edge.x, kf.odom_edge.y);
      }
      kf.travelled_m = travelled_m;
      auto cloud = std::make_shared<std::vector<RadarPoint>>();
      cloud->reserve(k.points.size());
      for (const auto& p : k.points) cloud->push_back({p.x, p.y, std::hypot(p.x, p.y), p.power, 0});
      kf.descriptor = k.descriptor.empty() ? computeM2DP(*cloud, params.loop_closing.m2dp)
                                           : Eigen::Map<const Eigen::VectorXf>(
                                                 k.descriptor.data(), static_cast<long>(k.descriptor.size()));
      kf.descriptor_flipped = computeM2DP(*cloud, params.loop_closing.m2dp, true);
      kf.cloud = std::move(cloud);
      state.keyframes.push_back(std::move(kf));
      closer.addMapKeyframe(state.keyframes.back().id);
    }
    // The map's own measurements: odometry edges replace the pose differences, loops stay loops.
    for (const auto& e : base.edges) {
      if (!index.count(e.from) || !index.count(e.to)) continue;
      const std::uint64_t from = index[e.from], to = index[e.to];
      if (e.kind == EdgeKind::Odometry && to == from + 1) {
        state.keyframes[to].odom_edge = e.relative;
      } else {
        AcceptedLoop loop;
        loop.from = from;
        loop.to = to;
        loop.relative = e.relative;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) loop.information(r, c) = e.information[3 * r + c];
        state.loops.push_back(loop);
      }
    }
    for (const auto& p : base.points) {
      SlamMapPoint mp;
      mp.xy = {p.x, p.y};
      for (const auto id : p.observed_by) {
        if (!index.count(id)) continue;
        const std::uint64_t k = index[id];
        mp.observations.push_back({k, inverseTransformPoint(state.keyframes[k].pose, mp.xy)});
      }
      if (mp.observations.empty()) continue;
      mp.reference = mp.observations.front().keyframe;
      state.points.push_back(std::move(mp));
    }
    state.session_first = next_keyframe = state.keyframes.size();
    state.anchored = false;
    travelled = travelled_m + 1e6;  // map keyframes are never "recent" for the loop detector
    sensor = base.meta.sensor;
  }

  SlamStep process(const CObservationRadarScan& scan) {
    if (finished) throw std::logic_error("RadarSlam::process after finish()");
    const auto t0 = std::chrono::steady_clock::now();
    if (anchors.empty() && state.session_first == 0)
      sensor = {static_cast<std::uint32_t>(scan.num_azimuths), static_cast<std::uint32_t>(scan.num_bins),
                scan.range_resolution_m, scan.range_offset_m};
    SlamStep step;
    step.odometry = odometry.process(scan);
    const OdometryStep& o = step.odometry;
    if (!anchors.empty()) travelled += std::hypot(o.pose.x - last_odom.x, o.pose.y - last_odom.y);
    last_odom = o.pose;
    if (o.new_keyframe) {
      KeyframeJob job;
      job.id = next_keyframe++;
      job.stamp = o.stamp;
      job.odom_pose = o.pose;
      job.lost = o.status == TrackingStatus::Lost;
      job.travelled_m = travelled;
      job.velocity = o.velocity;
      job.keypoints = o.keyframe_points;
      job.structure = o.keyframe_structure;
      job.observations = o.keyframe_observations;
      job.scan = std::make_shared<CObservationRadarScan>(scan);
      if (params.threads >= 2) {
        describe_queue.push(std::move(job));
      } else {
        mapper.describe(job);
        mapper.insert(job);
        closer.process(job.id);
      }
    }
    const ScanAnchor anchor{o.stamp, next_keyframe - 1, o.pose};
    anchors.push_back(anchor);
    std::lock_guard lock(state.mutex);
    step.pose = mapPose(anchor);
    ++state.stats.scans;
    state.stats.lost_scans += o.status == TrackingStatus::Lost;
    state.stats.tracking_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return step;
  }

  void finish() {
    if (finished) return;
    stopThreads();
    finished = true;
    bool any_loop = false;
    {
      std::lock_guard lock(state.mutex);
      for (const auto& l : state.loops) any_loop |= l.active;
    }
    if (!state.anchored)
      throw std::runtime_error("the new session found no verified loop to the map (no place in common?)");
    if (any_loop) optimiseAndCorrect(state, params);
  }

  KeyframeMap map() const {
    std::lock_guard lock(state.mutex);
    KeyframeMap m;
    m.meta.sensor = sensor;
    m.keyframes.reserve(state.keyframes.size());
    for (const auto& kf : state.keyframes) {
      Keyframe k;
      k.id = kf.id;
      k.stamp_ns = kf.stamp;
      k.pose = kf.pose;
      k.points.reserve(kf.cloud->size());
      for (const auto& p : *kf.cloud) k.points.push_back({p.x, p.y, p.power});
      k.descriptor.assign(kf.descriptor.data(), kf.descriptor.data() + kf.descriptor.size());
      m.keyframes.push_back(std::move(k));
      if (kf.session_start || kf.id == 0) continue;
      PoseGraphEdge e;
      e.from = kf.id - 1;
      e.to = kf.id;
      e.relative = kf.odom_edge;
      const Eigen::Matrix3d info =
          odometryInformation(params.odometry_edges, std::hypot(kf.odom_edge.x, kf.odom_edge.y), kf.lost) /
          state.odometry_variance_scale;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) e.information[3 * r + c] = info(r, c);
      e.kind = EdgeKind::Odometry;
      m.edges.push_back(e);
    }
    for (const auto& l : state.loops) {
      if (!l.active) continue;
      PoseGraphEdge e;
      e.from = l.from;
      e.to = l.to;
      e.relative = l.relative;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) e.information[3 * r + c] = l.information(r, c);
      e.kind = EdgeKind::Loop;
      m.edges.push_back(e);
    }
    for (const auto& mp : state.points) {
      if (mp.culled || static_cast<int>(mp.observations.size()) < params.local_mapping.min_observations)
        continue;
      MapPoint p;
      p.id = m.points.size();
      p.x = mp.xy.x();
      p.y = mp.xy.y();
      for (const auto& o : mp.observations) p.observed_by.push_back(o.keyframe);
      m.points.push_back(std::move(p));
    }
    return m;
  }
};

RadarSlam::RadarSlam(const SlamParams& params) : impl_(std::make_unique<Impl>(params)) {}
RadarSlam::~RadarSlam() = default;
SlamStep RadarSlam::process(const CObservationRadarScan& scan) { return impl_->process(scan); }
void RadarSlam::finish() { impl_->finish(); }
void RadarSlam::extend(const KeyframeMap& base) { impl_->extend(base); }

Trajectory RadarSlam::trajectory() const {
  std::lock_guard lock(impl_->state.mutex);
  Trajectory t;
  t.reserve(impl_->anchors.size());
  for (const auto& a : impl_->anchors) t.push_back({a.stamp, impl_->mapPose(a)});
  return t;
}
const Trajectory& RadarSlam::odometryTrajectory() const { return impl_->odometry.trajectory(); }
KeyframeMap RadarSlam::map() const { return impl_->map(); }
std::vector<LoopRecord> RadarSlam::loops() const {
  std::lock_guard lock(impl_->state.mutex);
  return impl_->state.records;
}
SlamStats RadarSlam::stats() const {
  std::lock_guard lock(impl_->state.mutex);
  SlamStats s = impl_->state.stats;
  s.keyframes = impl_->state.keyframes.size();
  s.map_points = 0;
  for (const auto& mp : impl_->state.points)
    s.map_points += !mp.culled &&
                    static_cast<int>(mp.observations.size()) >= impl_->params.local_mapping.min_observations;
  return s;
}
const SlamParams& RadarSlam::params() const { return impl_->params; }

}  // namespace radarslam
