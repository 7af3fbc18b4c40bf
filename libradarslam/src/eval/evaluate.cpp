#include "radarslam/eval/evaluate.h"

#include <cmath>

#include "radarslam/core/errors.h"

namespace radarslam::eval {

namespace {
void checkTrajectory(const Trajectory& t, const std::string& label) {
  if (const auto bad = firstNonIncreasingStamp(t))
    throw InputError(label, "timestamps do not strictly increase at pose " + std::to_string(*bad + 1));
  checkPlausiblePoses(t, label);
}
}  // namespace

void loadParams(const YamlParams& section, EvalParams& params) {
  section.get("kitti_lengths_m", params.kitti.lengths_m, Range::above(0, 1e5), 100);
  section.get("kitti_step_frames", params.kitti.step_frames, Range::closed(1, 1000000.0));
  section.get("max_gt_gap_s", params.max_gt_gap_s, Range::above(0, 1000000.0));
}

EvalReport evaluate(const Trajectory& est, const Trajectory& gt, const EvalParams& params,
                    const std::string& est_label, const std::string& gt_label) {
  checkTrajectory(est, est_label);
  checkTrajectory(gt, gt_label);
  if (gt.size() < 2) throw InputError(gt_label, "needs at least 2 poses, has " + std::to_string(gt.size()));
  EvalReport r;
  r.est_label = est_label;
  r.gt_label = gt_label;
  r.params = params;
  r.est_poses = est.size();
  r.gt_poses = gt.size();
  r.association = associate(est, gt, static_cast<StampNs>(std::llround(params.max_gt_gap_s * 1e9)));
  const Association& a = r.association;
  if (a.size() < 2)
    throw InputError(est_label, std::to_string(a.size()) + " of " + std::to_string(est.size()) +
                                    " estimated poses lie within the ground truth's time span (" +
                                    std::to_string(a.dropped_before_gt) + " before, " +
                                    std::to_string(a.dropped_after_gt) + " after, " +
                                    std::to_string(a.dropped_in_gt_gaps) +
                                    " in gaps): check the time stamps");
  const auto dist_gt = cumulativeDistances(a.gt);
  const auto dist_est = cumulativeDistances(a.est);
  r.gt_path_length_m = dist_gt.back();
  r.est_path_length_m = dist_est.back();
  r.duration_s = toSeconds(a.stamps.back() - a.stamps.front());
  r.kitti = computeKittiMetric(a.gt, a.est, params.kitti);
  r.ate = computeAte(a.gt, a.est);
  r.rpe = computeRpe(a.gt, a.est);
  return r;
}

}  // namespace radarslam::eval
