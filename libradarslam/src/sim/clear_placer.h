#pragma once
// Private to route_world.cpp: adds objects to a World so that none comes within road half-width +
// margin of any road piece. Segments keep their clear parts, circles and whole boxes (cars) are
// dropped when not clear.
#include "radarslam/sim/rng.h"
#include "radarslam/sim/road.h"
#include "radarslam/sim/world.h"

namespace radarslam::sim::detail {

class ClearPlacer {
 public:
  ClearPlacer(World& w, const std::vector<RoadPiece>& roads, double margin_m)
      : w_(w), index_(roads), margin_(margin_m) {}

  /// Clear at q with radius r. Objects are sampled at most 0.5 m apart and the clearance changes
  /// by at most the distance moved, so a 0.25 m reserve covers what lies between samples.
  bool clear(Vec2 q, double r = 0) const { return index_.clearance(q) - r > margin_ + 0.25; }

  /// The parts of a-b that are clear (runs of at least two samples).
  void segment(Vec2 a, Vec2 b, const Surface& s);
  void circle(Vec2 c, double r, const Surface& s);
  /// A box with its length along dir; `whole` = all four sides clear or nothing (a car).
  void box(Vec2 c, Vec2 dir, double length, double width, const Surface& s, bool whole);
  void tree(Vec2 c, Rng& rng);
  void pole(Vec2 c, Rng& rng);
  /// Small clutter: bins, bollards, signs, bushes.
  void clutter(Vec2 c, Rng& rng);

 private:
  World& w_;
  RoadIndex index_;
  double margin_;
};

}  // namespace radarslam::sim::detail
