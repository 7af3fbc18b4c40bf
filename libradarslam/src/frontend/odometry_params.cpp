#include "radarslam/frontend/odometry_params.h"

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, OdometryParams& p) {
  loadParams(yaml.section("cartesian"), p.cartesian);
  const YamlParams odo = yaml.section("odometry");

  const YamlParams kp = odo.section("keypoints");
  kp.get("detector", p.keypoints.detector);
  kp.get("max_keypoints", p.keypoints.max_keypoints);
  kp.get("fast_threshold", p.keypoints.fast_threshold);
  kp.get("pyramid_levels", p.keypoints.pyramid_levels);
  kp.get("patch_size", p.keypoints.patch_size);
  kp.get("blur_sigma_px", p.keypoints.blur_sigma_px);
  kp.get("subpixel", p.keypoints.subpixel);

  const YamlParams m = odo.section("matching");
  m.get("radius_m", p.matching.radius_m);
  m.get("init_radius_m", p.matching.init_radius_m);
  m.get("ratio", p.matching.ratio);
  m.get("max_descriptor_distance", p.matching.max_descriptor_distance);
  m.get("mutual", p.matching.mutual);

  const YamlParams o = odo.section("outliers");
  o.get("max_clique", p.outliers.max_clique);
  o.get("delta_c_m", p.outliers.delta_c_m);
  o.get("consistency", p.outliers.consistency);
  o.get("max_matches", p.outliers.max_matches);
  double steps = static_cast<double>(p.outliers.max_clique_steps);
  o.get("max_clique_steps", steps);
  p.outliers.max_clique_steps = static_cast<long>(steps);
  o.get("inlier_gate_m", p.outliers.inlier_gate_m);

  const YamlParams pa = odo.section("patch_alignment");
  pa.get("enabled", p.patch_alignment.enabled);
  pa.get("patch_radius_px", p.patch_alignment.patch_radius_px);
  pa.get("search_radius_px", p.patch_alignment.search_radius_px);
  pa.get("lk_iterations", p.patch_alignment.lk_iterations);
  pa.get("min_ncc", p.patch_alignment.min_ncc);
  pa.get("blur_sigma_px", p.patch_alignment.blur_sigma_px);
  pa.get("track_keyframe_points", p.patch_alignment.track_keyframe_points);
  pa.get("track_search_radius_px", p.patch_alignment.track_search_radius_px);
  pa.get("track_gate_m", p.patch_alignment.track_gate_m);

  const YamlParams r = odo.section("refine");
  r.get("iterations", p.refine.iterations);
  r.get("huber_m", p.refine.huber_m);
  r.get("azimuth_sigma_rad", p.refine.azimuth_sigma_rad);
  r.get("range_sigma_m", p.refine.range_sigma_m);

  const YamlParams k = odo.section("keyframes");
  k.get("max_translation_m", p.keyframes.max_translation_m);
  k.get("max_rotation_rad", p.keyframes.max_rotation_rad);
  k.get("min_inliers", p.keyframes.min_inliers);

  const YamlParams t = odo.section("tracking");
  t.get("min_inliers", p.tracking.min_inliers);
  t.get("min_range_m", p.tracking.min_range_m);
  t.get("max_speed_mps", p.tracking.max_speed_mps);
  t.get("keep_keyframe_when_lost", p.tracking.keep_keyframe_when_lost);
  t.get("motion_compensation", p.tracking.motion_compensation);
  t.get("acceleration_aware", p.tracking.acceleration_aware);
  t.get("compensation_passes", p.tracking.compensation_passes);
  t.get("max_prediction_gap_s", p.tracking.max_prediction_gap_s);

  const std::string& where = yaml.origin();
  if (p.outliers.consistency != "distance" && p.outliers.consistency != "displacement")
    throw InputError(where, "odometry.outliers.consistency must be 'distance' or 'displacement'");
  if (!(p.matching.radius_m > 0) || !(p.matching.init_radius_m > 0))
    throw InputError(where, "odometry.matching radii must be > 0");
  if (!(p.outliers.delta_c_m > 0)) throw InputError(where, "odometry.outliers.delta_c_m must be > 0");
  if (p.keypoints.max_keypoints < 10)
    throw InputError(where, "odometry.keypoints.max_keypoints must be >= 10");
  if (p.tracking.min_inliers < 3) throw InputError(where, "odometry.tracking.min_inliers must be >= 3");
  if (!(p.tracking.max_prediction_gap_s > 0))
    throw InputError(where, "odometry.tracking.max_prediction_gap_s must be > 0");
}

}  // namespace radarslam
