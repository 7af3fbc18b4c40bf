#pragma once
// The map's keyframes as a graph (issue #14, item 3: maps with the same street twice). Odometry
// edges connect keyframes driven one after the other, loop edges connect a revisit to the place it
// was merged with; an edge's length is its relative translation. A SLAM run that did not merge a
// revisit leaves two copies of a street that are close in space but far apart in this graph, and
// their relative pose is only as good as the odometry between them: the tracker registers against
// the keyframes within a bounded path distance of the one it is tracking (one copy, consistently),
// and treats the other copy as an ambiguity to report.
#include <cstddef>
#include <vector>

#include "radarslam/map/keyframe_map.h"

namespace radarslam {

class MapConnectivity {
 public:
  /// Keyframe indices (positions in map.keyframes) connected by map.edges (ids resolved; edges to
  /// unknown ids ignored). A map without any edge (e.g. hand-made) is treated as one chain in
  /// keyframe order.
  explicit MapConnectivity(const KeyframeMap& map);

  /// 1 for each keyframe whose shortest path from `from` is at most max_path_m (Dijkstra, bounded),
  /// 0 otherwise; all 1 when `from` is out of range.
  std::vector<char> within(std::size_t from, double max_path_m) const;

  /// The keyframe indices along the shortest path from `from` to `to` (Dijkstra, stopped at `to`),
  /// both included; empty when either is out of range or no path joins them.
  std::vector<std::size_t> path(std::size_t from, std::size_t to) const;

  std::size_t size() const { return adjacency_.size(); }

 private:
  struct Link {
    std::size_t to;
    double length_m;
  };
  /// Dijkstra from `from` over paths of at most max_path_m, stopped once `stop_at` is settled:
  /// each keyframe's path distance (+inf when not reached) and its predecessor on that path.
  struct Search {
    std::vector<double> distance;
    std::vector<std::size_t> previous;
  };
  Search search(std::size_t from, double max_path_m, std::size_t stop_at) const;
  std::vector<std::vector<Link>> adjacency_;
};

}  // namespace radarslam
