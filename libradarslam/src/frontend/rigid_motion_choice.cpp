#include "radarslam/frontend/rigid_motion_choice.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "radarslam/frontend/svd_pose.h"

namespace radarslam {

double rigidMotionLogLikelihood(const mrpt::math::TPose2D& pose, std::size_t n,
                                const MotionPrediction& prediction) {
  const double k2 = prediction.keypoint_sigma_m * prediction.keypoint_sigma_m;
  const double r2 = prediction.search_radius_m * prediction.search_radius_m;
  const double s2 =
      prediction.sigma_m * prediction.sigma_m + 2.0 * k2 / static_cast<double>(std::max<std::size_t>(1, n));
  const mrpt::math::TPose2D d = pose - prediction.predicted;
  return static_cast<double>(n) * std::log(r2 / (4.0 * k2)) - (d.x * d.x + d.y * d.y) / (2.0 * s2) -
         std::log(2.0 * std::numbers::pi * s2);
}

namespace {
Correspondences subset(const Correspondences& matches, const std::vector<int>& vertices) {
  Correspondences out;
  out.reserve(vertices.size());
  for (int v : vertices) out.push_back(matches[v]);
  return out;
}
}  // namespace

RigidMotionChoice chooseRigidMotion(const Correspondences& matches, const DenseGraph& graph,
                                    const std::vector<int>& first, const MotionPrediction& prediction,
                                    int min_inliers, long max_clique_steps) {
  RigidMotionChoice out{first, false};
  if (!(prediction.sigma_m > 0) || !(prediction.search_radius_m > 0) || !(prediction.keypoint_sigma_m > 0))
    return out;
  // The matches outside the first clique, and their graph.
  std::vector<char> in_first(graph.size(), 0);
  for (int v : first) in_first[v] = 1;
  std::vector<int> rest;
  for (int i = 0; i < graph.size(); ++i)
    if (!in_first[i]) rest.push_back(i);
  if (static_cast<int>(rest.size()) < min_inliers) return out;
  const CliqueResult second = maximumClique(graph.induced(rest), max_clique_steps);
  if (static_cast<int>(second.vertices.size()) < min_inliers) return out;
  std::vector<int> second_vertices;
  for (int v : second.vertices) second_vertices.push_back(rest[v]);
  std::sort(second_vertices.begin(), second_vertices.end());

  const auto first_pose = fitPoseSvd(subset(matches, first));
  const auto second_pose = fitPoseSvd(subset(matches, second_vertices));
  if (!first_pose || !second_pose) return out;
  if (rigidMotionLogLikelihood(*second_pose, second_vertices.size(), prediction) >
      rigidMotionLogLikelihood(*first_pose, first.size(), prediction)) {
    out.vertices = std::move(second_vertices);
    out.second = true;
  }
  return out;
}

}  // namespace radarslam
