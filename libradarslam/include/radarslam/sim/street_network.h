#pragma once
// An irregular street network for a seed, as one lap of a route through it: a long straight
// street starting at a cul-de-sac (turning circle: the dead end with a U-turn), a wide curve, a
// roundabout, a connector to a non-right-angle junction, and an irregular loop of curved streets
// driven once each way (forward, then a U-turn round the roundabout, then reversed), back round
// the roundabout and down the curve and the straight. Road widths vary per street. Consecutive
// laps chain (the lap ends at its start, heading the same way).
#include <cstdint>
#include <vector>

#include "radarslam/sim/route.h"
#include "radarslam/sim/route_world.h"

namespace radarslam::sim {

struct StreetNetwork {
  std::vector<RouteWaypoint> lap;
  std::vector<SceneZone> zones;  ///< the long straight's featureless wall
  double wall_length_m = 0;      ///< length of the straight covered by the wall zone
};

/// The network and its lap for `seed`; speeds come from `params` (city/country speed).
StreetNetwork generateStreetNetwork(std::uint64_t seed, const RouteParams& params);

}  // namespace radarslam::sim
