#include "radarslam/slam/slam_params.h"

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, SlamParams& p) {
  loadParams(yaml, p.odometry);
  const YamlParams slam = yaml.section("slam");
  slam.get("threads", p.threads);

  const YamlParams lm = slam.section("local_mapping");
  lm.get("bundle_adjustment", p.local_mapping.bundle_adjustment);
  lm.get("window_keyframes", p.local_mapping.window_keyframes);
  lm.get("interval_keyframes", p.local_mapping.interval_keyframes);
  lm.get("max_iterations", p.local_mapping.max_iterations);
  lm.get("observation_sigma_m", p.local_mapping.observation_sigma_m);
  lm.get("huber_sigmas", p.local_mapping.huber_sigmas);
  lm.get("min_observations", p.local_mapping.min_observations);
  lm.get("prior_sigma_xy_m", p.local_mapping.prior_sigma_xy_m);
  lm.get("prior_sigma_phi_rad", p.local_mapping.prior_sigma_phi_rad);

  const YamlParams oe = slam.section("odometry_edges");
  oe.get("sigma_xy_base_m", p.odometry_edges.sigma_xy_base_m);
  oe.get("sigma_xy_per_m", p.odometry_edges.sigma_xy_per_m);
  oe.get("sigma_phi_base_rad", p.odometry_edges.sigma_phi_base_rad);
  oe.get("sigma_phi_per_m", p.odometry_edges.sigma_phi_per_m);
  oe.get("lost_factor", p.odometry_edges.lost_factor);

  const YamlParams lc = slam.section("loop_closure");
  lc.get("enabled", p.loop_closing.enabled);
  lc.get("max_verifications", p.loop_closing.max_verifications);
  lc.get("max_verifications_after_loop", p.loop_closing.max_verifications_after_loop);
  lc.get("optimise_min_correction_m", p.loop_closing.optimise_min_correction_m);
  lc.get("optimise_min_correction_deg", p.loop_closing.optimise_min_correction_deg);
  lc.get("drift_fraction", p.loop_closing.drift_fraction);
  lc.get("loop_sigma_xy_m", p.loop_closing.loop_sigma_xy_m);
  lc.get("loop_sigma_phi_deg", p.loop_closing.loop_sigma_phi_deg);
  lc.get("drift_base_m", p.loop_closing.drift_base_m);
  lc.get("drift_base_deg", p.loop_closing.drift_base_deg);
  lc.get("drift_deg_per_m", p.loop_closing.drift_deg_per_m);
  loadParams(lc.section("peak_cloud"), p.loop_closing.peak_cloud);
  loadParams(lc.section("m2dp"), p.loop_closing.m2dp);
  loadParams(lc.section("detector"), p.loop_closing.detector);
  loadParams(lc.section("verifier"), p.loop_closing.verifier);
  loadParams(slam.section("pose_graph"), p.pose_graph);

  const std::string& where = yaml.origin();
  if (p.threads < 1) throw InputError(where, "slam.threads must be >= 1");
  if (p.local_mapping.window_keyframes < 2)
    throw InputError(where, "slam.local_mapping.window_keyframes must be >= 2");
  if (p.local_mapping.interval_keyframes < 1 ||
      p.local_mapping.interval_keyframes > p.local_mapping.window_keyframes)
    throw InputError(where, "slam.local_mapping.interval_keyframes must be in [1, window_keyframes]");
  if (p.local_mapping.min_observations < 2)
    throw InputError(where, "slam.local_mapping.min_observations must be >= 2");
  if (!(p.local_mapping.observation_sigma_m > 0) || !(p.local_mapping.prior_sigma_xy_m > 0) ||
      !(p.local_mapping.prior_sigma_phi_rad > 0))
    throw InputError(where, "slam.local_mapping sigmas must be > 0");
  if (!(p.odometry_edges.sigma_xy_base_m > 0) || !(p.odometry_edges.sigma_phi_base_rad > 0) ||
      p.odometry_edges.sigma_xy_per_m < 0 || p.odometry_edges.sigma_phi_per_m < 0 ||
      !(p.odometry_edges.lost_factor >= 1))
    throw InputError(where, "slam.odometry_edges: sigmas must be > 0 and lost_factor >= 1");
  if (p.loop_closing.max_verifications < 1)
    throw InputError(where, "slam.loop_closure.max_verifications must be >= 1");
}

}  // namespace radarslam
