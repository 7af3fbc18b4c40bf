// Keyframe culling before a map is saved; see map/keyframe_culling.h.
#include "radarslam/map/keyframe_culling.h"

#include <mrpt/poses/CPose2D.h>

#include <Eigen/Dense>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "radarslam/core/se2_covariance.h"

namespace radarslam {

namespace {

using Pose = mrpt::math::TPose2D;

Pose between(const Pose& a, const Pose& b) {
  return (mrpt::poses::CPose2D(b) - mrpt::poses::CPose2D(a)).asTPose();
}
Pose compose(const Pose& a, const Pose& b) {
  return (mrpt::poses::CPose2D(a) + mrpt::poses::CPose2D(b)).asTPose();
}

Eigen::Matrix3d toMatrix(const std::array<double, 9>& a) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = a[static_cast<std::size_t>(3 * r + c)];
  return m;
}
std::array<double, 9> toArray(const Eigen::Matrix3d& m) {
  std::array<double, 9> a{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[static_cast<std::size_t>(3 * r + c)] = m(r, c);
  return a;
}
/// Covariance of a relative pose from its information (a singular one: a large variance).
Eigen::Matrix3d covarianceOf(const std::array<double, 9>& information) {
  const Eigen::Matrix3d info = toMatrix(information);
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(info);
  if (!lu.isInvertible()) return Eigen::Matrix3d::Identity() * 1e6;
  return lu.inverse();
}

/// Kept keyframes on a grid of coverage-radius cells.
class CoverageGrid {
 public:
  explicit CoverageGrid(double cell) : cell_(cell) {}
  void add(std::size_t k, double x, double y) { cells_[key(cell(x), cell(y))].push_back(k); }
  /// The nearest kept keyframe within r of (x, y) whose path position is <= max_path, or -1.
  long nearest(const KeyframeMap& map, const std::vector<double>& path, double x, double y, double r,
               double max_path) const {
    long best = -1;
    double best_d = r;
    const long cx = cell(x), cy = cell(y);
    for (long ix = cx - 1; ix <= cx + 1; ++ix)
      for (long iy = cy - 1; iy <= cy + 1; ++iy) {
        const auto it = cells_.find(key(ix, iy));
        if (it == cells_.end()) continue;
        for (const std::size_t k : it->second) {
          if (path[k] > max_path) continue;
          const double d = std::hypot(map.keyframes[k].pose.x - x, map.keyframes[k].pose.y - y);
          if (d <= best_d) best_d = d, best = static_cast<long>(k);
        }
      }
    return best;
  }

 private:
  long cell(double v) const { return static_cast<long>(std::floor(v / cell_)); }
  static std::uint64_t key(long ix, long iy) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) << 32) |
           static_cast<std::uint32_t>(iy);
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

}  // namespace

CullingReport cullRedundantKeyframes(KeyframeMap& map, const KeyframeCullingParams& params) {
  CullingReport rep{map.keyframes.size(), map.keyframes.size(), map.edges.size(),
                    map.edges.size(),     map.points.size(),    map.points.size()};
  if (!params.enabled || map.keyframes.size() < 3) return rep;
  const std::size_t n = map.keyframes.size();
  std::vector<double> path(n, 0.0);  // driven path along map order
  for (std::size_t k = 1; k < n; ++k)
    path[k] = path[k - 1] + std::hypot(map.keyframes[k].pose.x - map.keyframes[k - 1].pose.x,
                                       map.keyframes[k].pose.y - map.keyframes[k - 1].pose.y);
  std::vector<long> cover(n, -1);  // the kept keyframe covering a dropped one
  CoverageGrid grid(params.coverage_radius_m);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& p = map.keyframes[k].pose;
    // The first and last keyframes stay: they anchor the graph's chain.
    if (k > 0 && k + 1 < n)
      cover[k] = grid.nearest(map, path, p.x, p.y, params.coverage_radius_m, path[k] - params.min_path_gap_m);
    if (cover[k] < 0) grid.add(k, p.x, p.y);
  }
  std::unordered_map<std::uint64_t, std::size_t> index_of;
  for (std::size_t k = 0; k < n; ++k) index_of[map.keyframes[k].id] = k;
  auto dropped = [&](std::uint64_t id) { return cover[index_of.at(id)] >= 0; };
  auto coverId = [&](std::uint64_t id) {
    return map.keyframes[static_cast<std::size_t>(cover[index_of.at(id)])].id;
  };

  // Odometry chain: consecutive edges through dropped keyframes composed into one.
  std::vector<PoseGraphEdge> edges;
  std::unordered_map<std::uint64_t, const PoseGraphEdge*> chain_from;  // odometry edge leaving a keyframe
  for (const auto& e : map.edges)
    if (e.kind == EdgeKind::Odometry && index_of.count(e.from) && index_of.count(e.to))
      chain_from[e.from] = &e;
  for (const auto& e : map.edges) {
    if (!index_of.count(e.from) || !index_of.count(e.to)) continue;  // not a keyframe of this map
    if (e.kind == EdgeKind::Odometry) {
      if (dropped(e.from)) continue;  // composed into the edge leaving the last kept keyframe
      PoseGraphEdge out = e;
      Eigen::Matrix3d cov = covarianceOf(e.information);
      std::unordered_set<std::uint64_t> seen{e.from};
      while (dropped(out.to) && chain_from.count(out.to) && seen.insert(out.to).second) {
        const PoseGraphEdge& next = *chain_from.at(out.to);
        cov = composeCovariance(out.relative, cov, next.relative, covarianceOf(next.information));
        out.relative = compose(out.relative, next.relative);
        out.to = next.to;
      }
      if (dropped(out.to)) continue;  // the chain ends in a dropped keyframe (no edge onwards)
      out.information = toArray(cov.inverse());
      edges.push_back(out);
    } else {
      // A loop edge: a dropped endpoint is replaced by the keyframe covering it.
      PoseGraphEdge out = e;
      if (dropped(out.from)) out.from = coverId(out.from);
      if (dropped(out.to)) out.to = coverId(out.to);
      if (out.from == out.to) continue;
      if (out.from != e.from || out.to != e.to)
        out.relative =
            between(map.keyframes[index_of.at(out.from)].pose, map.keyframes[index_of.at(out.to)].pose);
      edges.push_back(out);
    }
  }
  // Map points: dropped observers go; a point nobody kept observes goes.
  std::vector<MapPoint> points;
  for (auto& mp : map.points) {
    std::vector<std::uint64_t> obs;
    for (const std::uint64_t id : mp.observed_by)
      if (!index_of.count(id) || !dropped(id)) obs.push_back(id);
    if (obs.empty()) continue;
    mp.observed_by = std::move(obs);
    points.push_back(std::move(mp));
  }
  std::vector<Keyframe> kept;
  for (std::size_t k = 0; k < n; ++k)
    if (cover[k] < 0) kept.push_back(std::move(map.keyframes[k]));
  map.keyframes = std::move(kept);
  map.edges = std::move(edges);
  map.points = std::move(points);
  rep.keyframes_after = map.keyframes.size();
  rep.edges_after = map.edges.size();
  rep.points_after = map.points.size();
  return rep;
}

}  // namespace radarslam
