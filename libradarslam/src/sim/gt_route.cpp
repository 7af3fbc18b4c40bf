#include "radarslam/sim/gt_route.h"

#include <cmath>

#include "radarslam/io/ground_truth.h"

namespace radarslam::sim {

GroundTruthRoute routeFromOxfordGroundTruth(const std::filesystem::path& csv, const RouteParams& params,
                                            int traversal, double half_width_m, double piece_m) {
  const auto rows = readOxfordOdometryRows(csv);
  const Trajectory traj = chainOxfordOdometry(rows, csv);
  const StampNs shift =
      static_cast<StampNs>(std::llround((traversal - 1) * params.traversal2_delay_s * 1e6)) * kNsPerUs;
  GroundTruthRoute g;
  g.scan_starts.push_back(rows.front().destination_radar + shift);
  for (const auto& r : rows) g.scan_starts.push_back(r.source_radar + shift);
  Route& route = g.route;
  route.traversal = traversal;
  route.start_stamp = traj.front().stamp + shift;
  double s = 0;
  for (std::size_t k = 0; k < traj.size(); ++k) {
    const auto& q = traj[k].pose;
    if (k > 0) s += std::hypot(q.x - traj[k - 1].pose.x, q.y - traj[k - 1].pose.y);
    RouteSample r;
    r.s = s;
    r.t_arrive = r.t_depart = toSeconds(traj[k].stamp - traj.front().stamp);
    r.x = q.x, r.y = q.y, r.yaw = q.phi;
    if (k + 1 < traj.size()) {
      const auto& n = traj[k + 1].pose;
      r.speed =
          std::hypot(n.x - q.x, n.y - q.y) / std::max(toSeconds(traj[k + 1].stamp - traj[k].stamp), 1e-6);
    }
    route.samples.push_back(r);
  }
  // The road: the trajectory resampled every piece_m (stationary jitter adds nothing).
  Vec2 last{traj.front().pose.x, traj.front().pose.y};
  for (const auto& p : traj) {
    const Vec2 q{p.pose.x, p.pose.y};
    if ((q - last).norm() < piece_m) continue;
    g.roads.push_back({last, q, half_width_m});
    last = q;
  }
  return g;
}

}  // namespace radarslam::sim
