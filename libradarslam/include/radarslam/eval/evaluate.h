#pragma once
// One call that scores an estimated trajectory against ground truth the way radar-SLAM papers do:
// KITTI odometry metric (kitti_metric.h), ATE RMSE after SE(2) alignment and frame-to-frame RPE
// (pose_errors.h), after associating the two by time (association.h).
#include <string>

#include "radarslam/core/trajectory.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/eval/association.h"
#include "radarslam/eval/kitti_metric.h"
#include "radarslam/eval/pose_errors.h"

namespace radarslam::eval {

struct EvalParams {
  KittiParams kitti;
  /// Estimates between two ground-truth poses further apart than this are dropped (seconds).
  double max_gt_gap_s = 2.0;  ///< valid (0, 1000000]
};

/// Overrides from a YAML section: kitti_lengths_m (list), kitti_step_frames, max_gt_gap_s.
void loadParams(const YamlParams& section, EvalParams& params);

struct EvalReport {
  std::string est_label = "estimate";  ///< names for reports and plots (e.g. the file paths)
  std::string gt_label = "ground truth";
  EvalParams params;
  std::size_t est_poses = 0, gt_poses = 0;
  Association association;
  double gt_path_length_m = 0;   ///< along the associated ground truth
  double est_path_length_m = 0;  ///< along the associated estimate
  double duration_s = 0;         ///< first to last associated stamp
  KittiResult kitti;
  AteResult ate;
  RpeResult rpe;
};

/// Throws InputError("<label>", ...) if a trajectory has non-increasing stamps or non-finite poses,
/// or if fewer than 2 estimated poses fall within the ground truth.
EvalReport evaluate(const Trajectory& est, const Trajectory& gt, const EvalParams& params = {},
                    const std::string& est_label = "estimate", const std::string& gt_label = "ground truth");

}  // namespace radarslam::eval
