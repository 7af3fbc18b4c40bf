#include "radarslam/frontend/odometry_params.h"

#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, OdometryParams& p) {
  loadParams(yaml.section("cartesian"), p.cartesian);
  const YamlParams odo = yaml.section("odometry");

  const YamlParams kp = odo.section("keypoints");
  kp.get("detector", p.keypoints.detector);
  if (p.keypoints.detector != "orb" && p.keypoints.detector != "akaze" && p.keypoints.detector != "brisk" &&
      p.keypoints.detector != "fast_orb")
    kp.fail("detector", "must be orb, akaze, brisk or fast_orb, not '" + p.keypoints.detector + "'");
  kp.get("max_keypoints", p.keypoints.max_keypoints, Range::closed(10, 100000));
  kp.get("fast_threshold", p.keypoints.fast_threshold, Range::closed(1, 255));
  kp.get("pyramid_levels", p.keypoints.pyramid_levels, Range::closed(1, 16));
  kp.get("patch_size", p.keypoints.patch_size, Range::closed(5, 127));
  kp.get("blur_sigma_px", p.keypoints.blur_sigma_px, Range::closed(0, 20));
  kp.get("subpixel", p.keypoints.subpixel);

  const YamlParams m = odo.section("matching");
  m.get("radius_m", p.matching.radius_m, Range::above(0, 1000));
  m.get("init_radius_m", p.matching.init_radius_m, Range::above(0, 1000));
  m.get("ratio", p.matching.ratio, Range::above(0, 1));
  m.get("max_descriptor_distance", p.matching.max_descriptor_distance, Range::closed(0, 1024));
  m.get("mutual", p.matching.mutual);
  m.get("adaptive_radius", p.matching.adaptive_radius);
  m.get("radius_sigmas", p.matching.radius_sigmas, Range::above(0, 100));
  m.get("keypoint_sigma_px", p.matching.keypoint_sigma_px, Range::closed(0, 100));
  m.get("adaptive_min_samples", p.matching.adaptive_min_samples, Range::closed(1, 1e6));

  const YamlParams o = odo.section("outliers");
  o.get("max_clique", p.outliers.max_clique);
  o.get("delta_c_m", p.outliers.delta_c_m, Range::above(0, 100));
  o.get("consistency", p.outliers.consistency);
  if (p.outliers.consistency != "distance" && p.outliers.consistency != "displacement")
    o.fail("consistency", "must be 'distance' or 'displacement'");
  o.get("max_matches", p.outliers.max_matches, Range::closed(3, 5000));
  o.get("max_clique_steps", p.outliers.max_clique_steps, Range::closed(1, 1e8));
  o.get("inlier_gate_m", p.outliers.inlier_gate_m, Range::above(0, 100));
  o.get("second_motion", p.outliers.second_motion);

  const YamlParams pa = odo.section("patch_alignment");
  pa.get("enabled", p.patch_alignment.enabled);
  pa.get("patch_radius_px", p.patch_alignment.patch_radius_px, Range::closed(1, 32));
  pa.get("search_radius_px", p.patch_alignment.search_radius_px, Range::closed(0, 32));
  pa.get("lk_iterations", p.patch_alignment.lk_iterations, Range::closed(0, 100));
  pa.get("min_ncc", p.patch_alignment.min_ncc, Range::closed(-1, 1));
  pa.get("blur_sigma_px", p.patch_alignment.blur_sigma_px, Range::closed(0, 20));
  pa.get("track_keyframe_points", p.patch_alignment.track_keyframe_points);
  pa.get("track_search_radius_px", p.patch_alignment.track_search_radius_px, Range::closed(0, 32));
  pa.get("track_gate_m", p.patch_alignment.track_gate_m, Range::above(0, 100));

  const YamlParams r = odo.section("refine");
  r.get("iterations", p.refine.iterations, Range::closed(0, 1000));
  r.get("huber_m", p.refine.huber_m, Range::above(0, 100));
  r.get("azimuth_sigma_rad", p.refine.azimuth_sigma_rad, Range::closed(0, 1));
  r.get("range_sigma_m", p.refine.range_sigma_m, Range::closed(0, 10));
  r.get("structure_information", p.refine.structure.enabled);
  r.get("beam_blur_tolerance_deg", p.refine.structure.beam_blur_tolerance_deg, Range::closed(0, 90));
  r.get("motion_prior", p.refine.motion_prior);
  r.get("motion_prior_chi2", p.refine.motion_prior_chi2, Range::above(0, 1e6));

  const YamlParams k = odo.section("keyframes");
  k.get("max_translation_m", p.keyframes.max_translation_m, Range::above(0, 1000));
  k.get("max_rotation_rad", p.keyframes.max_rotation_rad, Range::above(0, 6.2832));
  k.get("min_inliers", p.keyframes.min_inliers, Range::closed(0, 100000));

  const YamlParams t = odo.section("tracking");
  t.get("min_inliers", p.tracking.min_inliers, Range::closed(3, 100000));
  t.get("min_range_m", p.tracking.min_range_m, Range::closed(0, 1000));
  t.get("max_speed_mps", p.tracking.max_speed_mps, Range::above(0, 1000));
  t.get("max_acceleration_mps2", p.tracking.max_acceleration_mps2, Range::above(0, 1000));
  t.get("keep_keyframe_when_lost", p.tracking.keep_keyframe_when_lost, Range::closed(0, 1000));
  t.get("motion_compensation", p.tracking.motion_compensation);
  t.get("acceleration_aware", p.tracking.acceleration_aware);
  t.get("compensation_passes", p.tracking.compensation_passes, Range::closed(0, 10));
  t.get("max_prediction_gap_s", p.tracking.max_prediction_gap_s, Range::above(0, 3600));

  loadParams(odo.section("doppler"), p.doppler);
}

}  // namespace radarslam
