#pragma once
#include <Eigen/Core>
// The full RadarSLAM system (paper Sec. III, Fig. 2): pose tracking in the caller's thread
// (frontend/odometry.h), local mapping with local bundle adjustment and loop closing each in its
// own thread, pose-graph optimisation after accepted loops, and the keyframe map.
//
//   scan -> RadarOdometry (III-A) --keyframe--> local mapping (III-B): peak cloud (Algorithm 1),
//           M2DP, map points, local BA, culling --> loop closing (III-C): kd-tree retrieval,
//           ICP+RANSAC verification --> pose graph (III-D) --> corrected keyframes and map points
//
// Every scan is anchored to the keyframe it was tracked from, so the output trajectory follows
// every correction. With params.threads == 1 everything runs in process() and results are
// deterministic.
#include <memory>
#include <string>
#include <vector>

#include "radarslam/core/trajectory.h"
#include "radarslam/frontend/odometry.h"
#include "radarslam/map/keyframe_map.h"
#include "radarslam/slam/slam_params.h"

namespace radarslam {

/// One loop-closure attempt (a verified candidate), for reports and tests.
struct LoopRecord {
  std::uint64_t query = 0, match = 0;  ///< keyframe ids (match is older)
  float descriptor_distance = 0;
  bool accepted = false;           ///< by geometric verification
  bool rejected_by_graph = false;  ///< accepted, then removed by the pose graph's chi^2 test
  std::string reason;              ///< why verification rejected it
  mrpt::math::TPose2D relative;    ///< query in match's frame (when accepted)
  double inlier_ratio = 0, ambiguity_ratio = 1;
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  ///< the verifier's estimate, of relative
  /// A partial loop (LoopClosingParams::accept_slide_loops): `relative` holds across
  /// slide_direction (a unit vector in the query's frame) and in heading, not along it.
  bool slide = false;
  Eigen::Vector2d slide_direction = Eigen::Vector2d::Zero();
  /// Refused as an ambiguous place, then accepted when the next keyframes' loops agreed with it
  /// (LoopClosingParams::confirm_ambiguous_keyframes).
  bool confirmed = false;
};

struct SlamStats {
  std::size_t scans = 0, lost_scans = 0, keyframes = 0, map_points = 0;
  std::size_t loop_candidates = 0, loops_accepted = 0, loops_rejected = 0, loops_rejected_by_graph = 0;
  std::size_t graph_optimisations = 0, bundle_adjustments = 0;
  /// Loops refused as ambiguous places, then confirmed by the next keyframes; and how often a chain
  /// of them was held back by a rival placement (LoopClosingParams::confirm_ambiguous_keyframes).
  std::size_t loops_confirmed = 0, confirmations_held_back = 0;
  std::size_t confirmations_withdrawn = 0;  ///< confirmed, then contradicted by a unique loop
  /// Candidates found by proximity where M2DP found none (LoopClosingParams::proximity_candidates).
  std::size_t proximity_candidates = 0;
  double tracking_ms = 0, local_mapping_ms = 0, loop_closing_ms = 0, graph_ms = 0;  ///< summed CPU wall time
};

struct SlamStep {
  OdometryStep odometry;     ///< the tracker's result (pose in the odometry frame)
  mrpt::math::TPose2D pose;  ///< current best estimate in the map frame
};

class RadarSlam {
 public:
  explicit RadarSlam(const SlamParams& params = {});
  ~RadarSlam();  ///< stops the threads (without the final optimisation: call finish())
  RadarSlam(const RadarSlam&) = delete;
  RadarSlam& operator=(const RadarSlam&) = delete;

  /// Extends `base` (a loaded map) with the scans that follow: call before the first process().
  /// The map's keyframes, map points and edges become part of the state; the new session is
  /// anchored to the map by its first verified loop to a map keyframe (relocalisation), then
  /// loops in both sessions enter one pose graph. map() then holds both sessions (keyframe ids
  /// renumbered 0..N-1 in the base map's order, then the new ones); trajectory() the new scans.
  /// finish() throws std::runtime_error if the new session never found the map. Throws
  /// std::invalid_argument for a map without keyframes or of raw (not motion-compensated) clouds.
  void extend(const KeyframeMap& base);

  /// Tracks one scan (time order) and hands new keyframes to local mapping. Blocks while local
  /// mapping is more than a bounded queue behind (memory stays bounded).
  SlamStep process(const CObservationRadarScan& scan);

  /// Waits for local mapping and loop closing to finish every keyframe, then runs a final
  /// pose-graph optimisation over every accepted loop. Call once, after the last scan.
  void finish();

  /// Every processed scan's pose in the map frame (after finish(): the final estimate).
  Trajectory trajectory() const;
  /// The tracker's own trajectory (odometry frame, no loop corrections).
  const Trajectory& odometryTrajectory() const;
  /// The keyframe map: keyframe poses and peak clouds, M2DP descriptors, map points seen by at
  /// least min_observations keyframes, odometry and (active) loop edges. metadata.sensor is set
  /// from the first scan; the caller fills the rest of the metadata.
  KeyframeMap map() const;
  std::vector<LoopRecord> loops() const;
  SlamStats stats() const;
  const SlamParams& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radarslam
