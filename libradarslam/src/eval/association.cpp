#include "radarslam/eval/association.h"

namespace radarslam::eval {

Association associate(const Trajectory& est, const Trajectory& gt, StampNs max_gt_gap_ns) {
  Association a;
  for (const auto& e : est) {
    if (gt.empty() || e.stamp < gt.front().stamp) {
      ++a.dropped_before_gt;
      continue;
    }
    if (e.stamp > gt.back().stamp) {
      ++a.dropped_after_gt;
      continue;
    }
    const auto g = interpolatePose(gt, e.stamp, max_gt_gap_ns);
    if (!g) {
      ++a.dropped_in_gt_gaps;
      continue;
    }
    a.stamps.push_back(e.stamp);
    a.est.push_back(e.pose);
    a.gt.push_back(*g);
  }
  return a;
}

}  // namespace radarslam::eval
