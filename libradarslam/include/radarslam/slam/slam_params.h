#pragma once
// Every parameter of the full RadarSLAM system (paper Sec. III), with defaults. config/<sensor>.yaml
// overrides the front end under `cartesian:`/`odometry:` (frontend/odometry_params.h) and the rest
// under `slam:` {local_mapping, odometry_edges, loop_closure {peak_cloud, m2dp, detector, verifier},
// pose_graph}.
#include "radarslam/backend/pose_graph.h"
#include "radarslam/frontend/odometry_params.h"
#include "radarslam/loop/loop_detector.h"
#include "radarslam/loop/loop_verifier.h"
#include "radarslam/loop/m2dp.h"
#include "radarslam/map/keyframe_culling.h"
#include "radarslam/map/map_layers.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

class YamlParams;

/// Local mapping (Sec. III-B): map points and local bundle adjustment.
struct LocalMappingParams {
  bool bundle_adjustment = true;
  int window_keyframes = 6;  ///< newest keyframes whose poses the local BA optimises; valid [2, 100]
  int interval_keyframes =
      2;  ///< a local BA after every this many keyframes (the window overlaps); valid [1, 100]
  int max_iterations = 8;  ///< Levenberg-Marquardt iterations per local BA; valid [0, 1000]
  double observation_sigma_m =
      0.1;  ///< keypoint position noise (Cartesian pixel 0.25 m / sqrt(12) ~ 0.07); valid (0, 100]
  double huber_sigmas = 2.0;  ///< robust kernel width, in sigmas; valid (0, 100]
  int min_observations = 3;  ///< map points seen by fewer keyframes are culled (paper: <= 2); valid [2, 1000]
  /// Odometry (keyframe-to-keyframe) priors inside the BA window, so a window with few shared
  /// points cannot drift freely: the tracked relative pose with these sigmas.
  double prior_sigma_xy_m = 0.3;      ///< valid (0, 1000]
  double prior_sigma_phi_rad = 0.01;  ///< valid (0, 10]
};

/// Odometry edges of the pose graph (Sec. III-D): keyframe-to-keyframe relative poses with a
/// diagonal information from sigma = base + per_metre * distance (a lost scan: x lost_factor).
struct OdometryEdgeParams {
  double sigma_xy_base_m = 0.02;      ///< valid (0, 100]
  double sigma_xy_per_m = 0.01;       ///< valid [0, 10]
  double sigma_phi_base_rad = 0.001;  ///< valid (0, 10]
  double sigma_phi_per_m = 0.0002;    ///< valid [0, 1]
  double lost_factor = 10.0;          ///< valid [1, 1000000]
};

/// Loop closing (Sec. III-C).
struct LoopClosingParams {
  bool enabled = true;
  PeakCloudParams peak_cloud;  ///< Algorithm 1
  M2DPParams m2dp;
  LoopDetectorParams detector;
  LoopVerifierParams verifier;
  int max_verifications = 2;  ///< candidates verified per keyframe (best descriptor first); valid [1, 100]
  /// ... and only this many when the previous keyframe closed a loop (along a revisit every
  /// keyframe has a loop; verification is the most expensive step).
  int max_verifications_after_loop = 1;  ///< valid [0, 100]
  /// Drift gate (ours; the paper relies on verification alone). A loop says where the query
  /// keyframe really is; odometry cannot have drifted arbitrarily far since the matched keyframe,
  /// so a loop implying a correction larger than drift_base_m + drift_fraction * (distance driven
  /// between the two keyframes), or a heading correction larger than drift_base_deg +
  /// drift_deg_per_m * distance, is rejected. Candidates whose current estimate is farther than
  /// verifier.max_translation_m + that bound are not even verified (saves most verifications).
  /// Repeated structure (a city of similar blocks) is what this stops: verification alone cannot
  /// tell two identical blocks apart. drift_fraction <= 0 disables the gate.
  double drift_fraction = 0.05;   ///< valid [0, 1]
  double drift_base_m = 5.0;      ///< valid [0, 10000]
  double drift_base_deg = 5.0;    ///< valid [0, 360]
  double drift_deg_per_m = 0.01;  ///< valid [0, 10]
  /// > 0: the drift gate is a chi^2(3) test instead of the linear bound above: the difference
  /// between the loop's relative pose and the current estimate's, under the covariance
  /// accumulated along the odometry chain between the two keyframes (OdometryEdgeParams,
  /// propagated; slam/loop_uncertainty.h) plus the loop's own. 16.27 = chi^2(3) at 99.9 %, the
  /// pose graph's own outlier bound. Candidates farther than the ellipse's largest semi-axis +
  /// verifier.max_translation_m are not verified. 0: the linear bound.
  double drift_gate_chi2 = 0;  ///< valid [0, 10000]
  /// After accepting a loop, the graph is optimised only if the loop moves the query keyframe by
  /// more than this from its current estimate; consistent loops (e.g. along a revisit already
  /// corrected) are just added. The final optimisation (finish()) uses every loop.
  double optimise_min_correction_m = 1.0;    ///< valid [0, 10000]
  double optimise_min_correction_deg = 1.0;  ///< valid [0, 360]
  /// Information of a loop edge: diag(1/sigma^2) with these sigmas - the spread of verified loop
  /// poses against ground truth on the simulator (max 0.25 m / 1.8 deg). The verifier's own
  /// Gauss-Newton information (loop/loop_verifier.h) is far more confident than that, which made
  /// the pose graph's chi^2 test drop hundreds of true loops; set these to 0 to use it anyway.
  double loop_sigma_xy_m = 0.2;     ///< valid (0, 100]
  double loop_sigma_phi_deg = 1.0;  ///< valid (0, 180]
  /// true: a loop edge's information is the verifier's estimate (loop/alignment_information.h),
  /// anisotropic where the place is degenerate, instead of the fixed sigmas above.
  bool loop_information_estimated = false;
  /// A place the verifier finds ambiguous only along one line (loop/loop_verifier.h `slide`: a
  /// straight featureless wall; not a street that also fits turned by 180 deg; every other test passed)
  /// becomes a partial loop: its edge constrains the offset across the line and the heading, and along the
  /// line has the variance of an unconstrained direction (loopInformation's 1e9 m^2). The drift
  /// gate and the graph's chi^2 test then judge it on what it constrains. Only once the session is
  /// anchored (a partial loop cannot place a new session in a loaded map).
  bool accept_slide_loops = false;
  /// A place the verifier finds ambiguous only because of rivals the drift gate would refuse (every
  /// rival's relative pose implies a correction beyond the bound; every other test passed) is
  /// unique where the loop can be, and the loop is accepted (then gated like any other). Needs the
  /// drift gate (drift_fraction > 0) and an anchored session.
  bool ambiguity_within_drift_bound = false;
  /// Where the descriptor search returns no candidate, the keyframes the drift gate allows — driven
  /// at least detector.exclude_recent_distance_m before the query and, in the current map, within
  /// verifier.max_translation_m + the drift bound of it (the candidates the gate would let through
  /// anyway) — are candidates instead, nearest first, verified as M2DP's are (max_verifications;
  /// ours, as proximity-based loop search in lidar SLAM). The pose graph's uncertainty says where a revisit
  /// can be; M2DP misses some (a revisit in the opposite direction one lane over, docs/slam.md).
  /// Needs the drift gate (drift_fraction > 0) and an anchored session.
  bool proximity_candidates = true;
  /// A place the verifier refused as ambiguous only (every other test passed) becomes a loop once
  /// the best alignments of this many queries, each within confirm_max_gap_keyframes keyframes of
  /// the previous, agree pairwise (chi^2(3) under both loops' covariances, the bound
  /// pose_graph.loop_chi2_gate), no rival placement is agreed on by two of them or by a unique loop,
  /// and its correction is within the drift bound of the shortest path through the graph; a unique
  /// loop that contradicts it later withdraws it (slam/loop_confirmation.h, docs/slam.md). 3: chosen on
  /// the train split (0 false loops left). 0 = off; valid 0 or [2, 100]
  int confirm_ambiguous_keyframes = 3;
  /// The largest gap between consecutive queries of such a chain (keyframes, ~2 m each); valid [1, 100]
  int confirm_max_gap_keyframes = 3;
};

struct SlamParams {
  OdometryParams odometry;
  LocalMappingParams local_mapping;
  OdometryEdgeParams odometry_edges;
  LoopClosingParams loop_closing;
  PoseGraphParams pose_graph;
  /// Applied by `radarslam map` before saving (map/keyframe_culling.h), not during the run.
  KeyframeCullingParams keyframe_culling;
  /// 1: everything runs in the caller's thread (deterministic); >= 2: local mapping and loop
  /// closing run in their own threads, as in the paper, and keyframe description (peak cloud,
  /// M2DP) in a third, ahead of local mapping.
  int threads = 3;  ///< valid [1, 64]
  /// The published layers saved with the map (section `map_layers:`, map/map_layers.h).
  MapLayerParams map_layers;
};

/// Overrides `params` from `yaml` (the front end via loadParams(yaml, params.odometry), the rest
/// from the `slam:` section, the map layers from `map_layers:`). Throws InputError for bad values.
void loadParams(const YamlParams& yaml, SlamParams& params);

}  // namespace radarslam
