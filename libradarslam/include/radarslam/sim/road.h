#pragma once
// Roads as the route worlds see them: the centreline as straight pieces, each with the half-width
// of its carriageway, and the clearance of a point from all of them (an object is "on the road"
// when its clearance is not positive).
#include <cstdint>
#include <vector>

#include "radarslam/sim/world.h"

namespace radarslam::sim {

struct RoadPiece {
  Vec2 a, b;
  double half_width = 6;  ///< centreline to the carriageway's edge, m
};

/// Distance from p to the segment a-b.
double distanceToSegment(Vec2 p, Vec2 a, Vec2 b);

/// Nearest-road queries through a uniform grid of the pieces.
class RoadIndex {
 public:
  explicit RoadIndex(const std::vector<RoadPiece>& pieces, double cell_m = 20.0);
  /// min over pieces of (distance to the piece - its half-width), capped at `cap`. Exact when
  /// below one cell (every piece that close is listed in p's cell); otherwise >= one cell or cap.
  double clearance(Vec2 p, double cap = 30.0) const;
  const std::vector<RoadPiece>& pieces() const { return pieces_; }

 private:
  std::vector<RoadPiece> pieces_;
  double cell_ = 20, x0_ = 0, y0_ = 0, reach_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_, items_;  // CSR
};

}  // namespace radarslam::sim
