#include "graph_optimiser.h"

#include <chrono>

#include "radarslam/backend/pose_graph.h"
#include "radarslam/core/log.h"

namespace radarslam::slam_detail {

Eigen::Matrix3d odometryInformation(const OdometryEdgeParams& p, double distance_m, bool lost) {
  const double k = lost ? p.lost_factor : 1.0;
  const double sxy = k * (p.sigma_xy_base_m + p.sigma_xy_per_m * distance_m);
  const double sphi = k * (p.sigma_phi_base_rad + p.sigma_phi_per_m * distance_m);
  return Eigen::Vector3d(1 / (sxy * sxy), 1 / (sxy * sxy), 1 / (sphi * sphi)).asDiagonal();
}

bool optimiseAndCorrect(SlamState& state, const SlamParams& params) {
  const auto t0 = std::chrono::steady_clock::now();
  PoseGraph graph(params.pose_graph);
  std::vector<std::size_t> loop_of_edge;  // graph edge -> index in state.loops (or npos)
  std::size_t n = 0;
  {
    std::lock_guard lock(state.mutex);
    n = state.keyframes.size();
    if (n < 2) return false;
    for (const auto& kf : state.keyframes) graph.addNode(kf.pose);
    for (std::size_t i = 1; i < n; ++i) {
      const auto& kf = state.keyframes[i];
      if (kf.session_start) continue;
      graph.addOdometryEdge(
          i - 1, i, kf.odom_edge,
          odometryInformation(params.odometry_edges, std::hypot(kf.odom_edge.x, kf.odom_edge.y), kf.lost) /
              state.odometry_variance_scale);
      loop_of_edge.push_back(static_cast<std::size_t>(-1));
    }
    if (!state.anchored) return false;  // the new session is not connected to the map yet
    for (std::size_t l = 0; l < state.loops.size(); ++l) {
      const auto& loop = state.loops[l];
      if (!loop.active || loop.to >= n) continue;
      graph.addLoopEdge(loop.from, loop.to, loop.relative, loop.information);
      loop_of_edge.push_back(l);
    }
  }
  const PoseGraphReport report = graph.optimize();

  std::lock_guard lock(state.mutex);
  for (const std::size_t e : report.rejected_edges) {
    const std::size_t l = loop_of_edge.at(e);
    if (l == static_cast<std::size_t>(-1)) continue;
    state.loops[l].active = false;
    if (state.loops[l].record != AcceptedLoop::kNoRecord)
      state.records[state.loops[l].record].rejected_by_graph = true;
    ++state.stats.loops_rejected_by_graph;
    logger().logFmt(mrpt::system::LVL_DEBUG, "slam: pose graph rejected loop %llu -> %llu",
                    static_cast<unsigned long long>(state.loops[l].from),
                    static_cast<unsigned long long>(state.loops[l].to));
  }
  std::vector<TPose2D> old_poses(state.keyframes.size());
  for (std::size_t i = 0; i < state.keyframes.size(); ++i) old_poses[i] = state.keyframes[i].pose;
  for (std::size_t i = 0; i < n; ++i) state.keyframes[i].pose = graph.pose(i);
  for (std::size_t i = n; i < state.keyframes.size(); ++i)
    state.keyframes[i].pose = compose(state.keyframes[i - 1].pose, between(old_poses[i - 1], old_poses[i]));
  for (auto& mp : state.points) {
    if (mp.culled) continue;
    mp.xy = transformPoint(state.keyframes[mp.reference].pose,
                           inverseTransformPoint(old_poses[mp.reference], mp.xy));
  }
  ++state.corrections;
  ++state.stats.graph_optimisations;
  state.stats.graph_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  logger().logFmt(mrpt::system::LVL_DEBUG, "slam: pose graph %zu nodes, chi2 %.1f -> %.1f, %zu iterations", n,
                  report.chi2_initial, report.chi2_final, report.iterations);
  return true;
}

}  // namespace radarslam::slam_detail
