#include "local_mapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_set>

#include "radarslam/slam/local_bundle_adjustment.h"

namespace radarslam::slam_detail {

namespace {
// An observation's information shape, stored in three floats (xx, xy, yy) per map point observation.
constexpr std::array<float, 3> kIsotropic{1.0f, 0.0f, 1.0f};
std::array<float, 3> compact(const Eigen::Matrix2d& w) {
  return {static_cast<float>(w(0, 0)), static_cast<float>(0.5 * (w(0, 1) + w(1, 0))),
          static_cast<float>(w(1, 1))};
}
Eigen::Matrix2d expand(const std::array<float, 3>& s) {
  Eigen::Matrix2d w;
  w << s[0], s[1], s[1], s[2];
  return w;
}
}  // namespace

void LocalMapper::describe(KeyframeJob& job) const {
  const auto t0 = std::chrono::steady_clock::now();
  auto cloud = std::make_shared<std::vector<RadarPoint>>(motionCompensated(
      extractPeakCloud(*job.scan, params_.loop_closing.peak_cloud), *job.scan, job.velocity));
  job.descriptor = computeM2DP(*cloud, params_.loop_closing.m2dp);
  job.descriptor_flipped = computeM2DP(*cloud, params_.loop_closing.m2dp, true);
  job.cloud = std::move(cloud);
  job.scan.reset();  // not needed further: the scan's memory goes back now
  job.describe_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void LocalMapper::insert(const KeyframeJob& job) {
  if (!job.cloud) {  // not described yet (a caller without the describe stage)
    KeyframeJob described = job;
    describe(described);
    insert(described);
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  SlamKeyframe kf;
  kf.id = job.id;
  kf.stamp = job.stamp;
  kf.odom_pose = job.odom_pose;
  kf.lost = job.lost;
  kf.travelled_m = job.travelled_m;
  kf.descriptor = job.descriptor;
  kf.descriptor_flipped = job.descriptor_flipped;
  kf.cloud = job.cloud;
  kf.keypoints = job.keypoints;
  kf.keypoint_structure = job.structure;
  kf.keypoint_point.assign(job.keypoints.size(), -1);
  kf.keypoint_offset.assign(job.keypoints.size(), Eigen::Vector2d::Zero());
  {
    std::lock_guard lock(state_.mutex);
    if (job.id != state_.keyframes.size()) throw std::logic_error("local mapping: keyframes out of order");
    if (job.id == state_.session_first) {
      kf.pose = job.odom_pose;
      kf.session_start = job.id > 0;
    } else {
      const SlamKeyframe& prev = state_.keyframes.back();
      kf.odom_edge = kf.tracked_edge = between(prev.odom_pose, job.odom_pose);
      kf.pose = compose(prev.pose, kf.odom_edge);
    }
    associate(kf, job);
    state_.keyframes.push_back(std::move(kf));
    const int window = params_.local_mapping.window_keyframes;
    if (job.id >= static_cast<std::uint64_t>(window)) retire(job.id - window);
  }
  if (params_.local_mapping.bundle_adjustment && job.id > state_.session_first &&
      (job.id - state_.session_first) % params_.local_mapping.interval_keyframes == 0)
    bundleAdjust(job.id);
  std::lock_guard lock(state_.mutex);
  state_.stats.local_mapping_ms +=
      job.describe_ms +
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void LocalMapper::associate(SlamKeyframe& kf, const KeyframeJob& job) {
  if (job.id == state_.session_first || job.lost) return;
  SlamKeyframe& prev = state_.keyframes.back();
  // An offset measured in the previous keyframe's frame, rotated into this one's (v_kf = R^T v_prev).
  const double c = std::cos(kf.tracked_edge.phi), s = std::sin(kf.tracked_edge.phi);
  for (const KeyframeObservation& o : job.observations) {
    const int pi = o.ref_index, ci = o.cur_index;
    if (pi < 0 || static_cast<std::size_t>(pi) >= prev.keypoints.size() ||
        static_cast<std::size_t>(ci + 1) > kf.keypoints.size() || (ci >= 0 && kf.keypoint_point[ci] >= 0))
      continue;
    std::int64_t& id = prev.keypoint_point[pi];
    if (id < 0) {
      SlamMapPoint mp;
      mp.xy = transformPoint(prev.pose, prev.keypoints[pi]);
      mp.reference = prev.id;
      mp.observations.push_back(
          {prev.id, prev.keypoints[pi],
           prev.keypoint_structure.empty() ? kIsotropic : compact(prev.keypoint_structure[pi])});
      id = static_cast<std::int64_t>(state_.points.size());
      state_.points.push_back(std::move(mp));
    }
    const Eigen::Vector2d& d = prev.keypoint_offset[pi];
    const Eigen::Vector2d z = o.xy + Eigen::Vector2d(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    state_.points[id].observations.push_back({kf.id, z, compact(o.information)});
    if (ci >= 0) {
      kf.keypoint_point[ci] = id;
      kf.keypoint_offset[ci] = z - kf.keypoints[ci];
    }
  }
}

void LocalMapper::retire(std::uint64_t id) {
  // The keyframe leaves the BA window: its association data goes, and so do the map points seen by
  // too few keyframes that can gain no more observations (paper: points seen by <= 2 culled). A
  // point gains one only through the keyframe that registered its newest one (keypoint_point), so it
  // is complete if that is this keyframe, or if the next keyframe measured it without registering it
  // (a tracked keyframe point, not a descriptor inlier): no later window reaches such a point.
  SlamKeyframe& kf = state_.keyframes[id];
  std::unordered_set<std::int64_t> registered_next;
  if (id + 1 < state_.keyframes.size())
    registered_next.insert(state_.keyframes[id + 1].keypoint_point.begin(),
                           state_.keyframes[id + 1].keypoint_point.end());
  for (const std::int64_t p : kf.keypoint_point) {
    if (p < 0 || state_.points[p].culled) continue;
    SlamMapPoint& mp = state_.points[p];
    const std::uint64_t newest = mp.observations.back().keyframe;
    const bool complete = newest == id || (newest == id + 1 && !registered_next.count(p));
    if (complete && static_cast<int>(mp.observations.size()) < params_.local_mapping.min_observations) {
      mp.culled = true;
      mp.observations.clear();
      mp.observations.shrink_to_fit();
    }
  }
  // Swapped with empty vectors: `v = {}` is assign(initializer_list), which keeps the capacity (on
  // the Oxford route every keyframe kept ~80 KB of association data to the end of the run).
  std::vector<Eigen::Vector2d>().swap(kf.keypoints);
  std::vector<Eigen::Matrix2d>().swap(kf.keypoint_structure);
  std::vector<std::int64_t>().swap(kf.keypoint_point);
  std::vector<Eigen::Vector2d>().swap(kf.keypoint_offset);
}

void LocalMapper::bundleAdjust(std::uint64_t newest) {
  const auto& lp = params_.local_mapping;
  BAProblem pb;
  std::map<std::uint64_t, std::size_t> pose_index;  // keyframe id -> problem pose
  std::vector<std::uint64_t> pose_ids;
  std::vector<std::size_t> point_ids;
  std::uint64_t corrections = 0;
  const std::uint64_t first = std::max<std::uint64_t>(
      state_.session_first,
      newest + 1 > static_cast<std::uint64_t>(lp.window_keyframes) ? newest + 1 - lp.window_keyframes : 0);
  {
    std::lock_guard lock(state_.mutex);
    corrections = state_.corrections;
    auto addPose = [&](std::uint64_t id, bool fixed) {
      auto [it, inserted] = pose_index.emplace(id, pb.poses.size());
      if (inserted) {
        pb.poses.push_back(state_.keyframes[id].pose);
        pb.fixed.push_back(fixed);
        pose_ids.push_back(id);
      }
      return it->second;
    };
    // The oldest window keyframe is fixed when nothing outside the window anchors the window.
    for (std::uint64_t id = first; id <= newest; ++id) addPose(id, id == first);
    // The window's points in order of first sight. A set of the window's points, not a flag per
    // map point: that one was zeroed per BA, O(map size) each time, quadratic over a long run.
    std::unordered_set<std::int64_t> seen;
    for (std::uint64_t id = first; id <= newest; ++id) {
      for (const std::int64_t p : state_.keyframes[id].keypoint_point) {
        if (p < 0 || state_.points[p].culled || !seen.insert(p).second) continue;
        const std::size_t j = pb.points.size();
        pb.points.push_back(state_.points[p].xy);
        point_ids.push_back(static_cast<std::size_t>(p));
        for (const auto& o : state_.points[p].observations)
          pb.observations.push_back({addPose(o.keyframe, o.keyframe < first), j, o.z, expand(o.shape)});
      }
    }
    for (std::uint64_t id = first + 1; id <= newest; ++id)
      if (!state_.keyframes[id].lost)
        pb.priors.push_back({pose_index.at(id - 1), pose_index.at(id), state_.keyframes[id].tracked_edge});
  }
  if (pb.observations.empty()) return;
  solveLocalBundleAdjustment(pb, lp);

  std::lock_guard lock(state_.mutex);
  ++state_.stats.bundle_adjustments;
  if (state_.corrections != corrections) return;  // a loop correction moved everything meanwhile
  for (std::size_t i = 0; i < pose_ids.size(); ++i)
    if (!pb.fixed[i]) state_.keyframes[pose_ids[i]].pose = pb.poses[i];
  for (std::size_t j = 0; j < point_ids.size(); ++j) state_.points[point_ids[j]].xy = pb.points[j];
  for (std::uint64_t id = first + 1; id <= newest; ++id)
    if (!state_.keyframes[id].lost)
      state_.keyframes[id].odom_edge = between(state_.keyframes[id - 1].pose, state_.keyframes[id].pose);
  // Keyframes inserted after `newest` meanwhile (threads) follow their predecessor.
  for (std::uint64_t id = newest + 1; id < state_.keyframes.size(); ++id)
    state_.keyframes[id].pose = compose(state_.keyframes[id - 1].pose, state_.keyframes[id].odom_edge);
}

}  // namespace radarslam::slam_detail
