#pragma once
// A world generated around an arbitrary route: objects beside the road (never on it), chosen by
// world position (hashes of spatial cells, not the order of the route), so a street driven twice,
// in either direction, sees the same objects. Scene types per stretch of road: urban canyon,
// suburban, open country / dual carriageway, car park, tree-lined avenue, and a long featureless
// wall (the degenerate case for odometry). Parked cars and moving traffic change per traversal.
#include <cstdint>
#include <string>
#include <vector>

#include "radarslam/sim/road.h"
#include "radarslam/sim/world.h"

namespace radarslam::sim {

enum class Scene : std::uint8_t { Mixed, Urban, Suburban, Country, Carpark, Avenue, Wall };

/// "mixed", "urban", ... -> Scene; anything else is an InputError naming `option`.
Scene parseScene(const std::string& name, const std::string& option = "--scene");
const char* sceneName(Scene s);

/// A region (capsule around a-b) whose scene is fixed, e.g. the long wall of a street network.
struct SceneZone {
  Vec2 a, b;
  double radius_m = 40;
  Scene scene = Scene::Wall;
};

struct RouteWorldParams {
  double margin_m = 0.5;         ///< every object beyond road half-width + margin; valid [0.1, 10]
  double scene_cell_m = 180;     ///< mixed scenes: one scene per cell of this size; valid [20, 5000]
  double road_half_width_m = 6;  ///< routes without widths (from a trajectory); valid [2, 30]
  double wall_length_m = 350;    ///< the featureless wall's cell (length); valid [300, 400]
};

/// A wall zone over the first stretch of `roads` that stays within 6 m of a straight line for
/// `length_m` (none if there is no such stretch): the degenerate case on a real route.
std::vector<SceneZone> longStraightWallZones(const std::vector<RoadPiece>& roads, double length_m);

/// Generates the world around `roads` (the route's centreline pieces). `scene` = Mixed picks a
/// scene per cell; zones override it. `traversal` redraws parked cars and traffic only.
/// `world.params` supplies parked_car_probability and moving_vehicles.
World generateRouteWorld(const std::vector<RoadPiece>& roads, const RouteWorldParams& params,
                         const WorldParams& world_params, Scene scene, const std::vector<SceneZone>& zones,
                         std::uint64_t seed, int traversal);

}  // namespace radarslam::sim
