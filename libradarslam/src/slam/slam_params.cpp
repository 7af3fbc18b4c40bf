#include "radarslam/slam/slam_params.h"

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, SlamParams& p) {
  loadParams(yaml, p.odometry);
  loadParams(yaml.section("map_layers"), p.map_layers);
  const YamlParams slam = yaml.section("slam");
  slam.get("threads", p.threads, Range::closed(1, 64));

  const YamlParams lm = slam.section("local_mapping");
  lm.get("bundle_adjustment", p.local_mapping.bundle_adjustment);
  lm.get("window_keyframes", p.local_mapping.window_keyframes, Range::closed(2, 100));
  lm.get("interval_keyframes", p.local_mapping.interval_keyframes, Range::closed(1, 100));
  lm.get("max_iterations", p.local_mapping.max_iterations, Range::closed(0, 1000));
  lm.get("observation_sigma_m", p.local_mapping.observation_sigma_m, Range::above(0, 100));
  lm.get("huber_sigmas", p.local_mapping.huber_sigmas, Range::above(0, 100));
  lm.get("min_observations", p.local_mapping.min_observations, Range::closed(2, 1000));
  lm.get("prior_sigma_xy_m", p.local_mapping.prior_sigma_xy_m, Range::above(0, 1000));
  lm.get("prior_sigma_phi_rad", p.local_mapping.prior_sigma_phi_rad, Range::above(0, 10));

  const YamlParams kc = slam.section("keyframe_culling");
  kc.get("enabled", p.keyframe_culling.enabled);
  kc.get("coverage_radius_m", p.keyframe_culling.coverage_radius_m, Range::above(0, 1000));
  kc.get("min_path_gap_m", p.keyframe_culling.min_path_gap_m, Range::closed(0, 1000000.0));

  const YamlParams oe = slam.section("odometry_edges");
  oe.get("sigma_xy_base_m", p.odometry_edges.sigma_xy_base_m, Range::above(0, 100));
  oe.get("sigma_xy_per_m", p.odometry_edges.sigma_xy_per_m, Range::closed(0, 10));
  oe.get("sigma_phi_base_rad", p.odometry_edges.sigma_phi_base_rad, Range::above(0, 10));
  oe.get("sigma_phi_per_m", p.odometry_edges.sigma_phi_per_m, Range::closed(0, 1));
  oe.get("lost_factor", p.odometry_edges.lost_factor, Range::closed(1, 1000000.0));

  const YamlParams lc = slam.section("loop_closure");
  lc.get("enabled", p.loop_closing.enabled);
  lc.get("max_verifications", p.loop_closing.max_verifications, Range::closed(1, 100));
  lc.get("max_verifications_after_loop", p.loop_closing.max_verifications_after_loop, Range::closed(0, 100));
  lc.get("optimise_min_correction_m", p.loop_closing.optimise_min_correction_m, Range::closed(0, 10000.0));
  lc.get("optimise_min_correction_deg", p.loop_closing.optimise_min_correction_deg, Range::closed(0, 360));
  lc.get("drift_fraction", p.loop_closing.drift_fraction, Range::closed(0, 1));
  lc.get("loop_sigma_xy_m", p.loop_closing.loop_sigma_xy_m, Range::above(0, 100));
  lc.get("loop_sigma_phi_deg", p.loop_closing.loop_sigma_phi_deg, Range::above(0, 180));
  lc.get("loop_information_estimated", p.loop_closing.loop_information_estimated);
  lc.get("accept_slide_loops", p.loop_closing.accept_slide_loops);
  lc.get("ambiguity_within_drift_bound", p.loop_closing.ambiguity_within_drift_bound);
  lc.get("proximity_candidates", p.loop_closing.proximity_candidates);
  lc.get("confirm_ambiguous_keyframes", p.loop_closing.confirm_ambiguous_keyframes, Range::closed(0, 100));
  if (p.loop_closing.confirm_ambiguous_keyframes == 1)
    lc.fail("confirm_ambiguous_keyframes", "must be 0 (off) or >= 2");
  lc.get("confirm_max_gap_keyframes", p.loop_closing.confirm_max_gap_keyframes, Range::closed(1, 100));
  lc.get("drift_gate_chi2", p.loop_closing.drift_gate_chi2, Range::closed(0, 10000));
  lc.get("drift_base_m", p.loop_closing.drift_base_m, Range::closed(0, 10000.0));
  lc.get("drift_base_deg", p.loop_closing.drift_base_deg, Range::closed(0, 360));
  lc.get("drift_deg_per_m", p.loop_closing.drift_deg_per_m, Range::closed(0, 10));
  loadParams(lc.section("peak_cloud"), p.loop_closing.peak_cloud);
  loadParams(lc.section("m2dp"), p.loop_closing.m2dp);
  loadParams(lc.section("detector"), p.loop_closing.detector);
  loadParams(lc.section("verifier"), p.loop_closing.verifier);
  loadParams(slam.section("pose_graph"), p.pose_graph);

  if (p.local_mapping.interval_keyframes > p.local_mapping.window_keyframes)
    lm.fail("interval_keyframes",
            "must be <= window_keyframes (" + std::to_string(p.local_mapping.window_keyframes) + ")");
}

}  // namespace radarslam
