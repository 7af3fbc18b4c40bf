#pragma once
// A procedurally generated 2D world for the radar simulator, deterministic by seed: a grid of
// city blocks (building facades with roughness and varying reflectivity, an open square, a park),
// street furniture (parked cars, poles, trees, fences, hedges), a long "corridor" street of
// identical terraced facades (an ambiguous place for loop closure), a countryside loop with sparse
// structure (hedgerows, lone trees, farm buildings, power poles), and moving vehicles.
// Ray casting goes through a uniform grid index so a beam only tests what lies along it.
#include <cstdint>
#include <vector>

namespace radarslam::sim {

struct Vec2 {
  double x = 0, y = 0;
  Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  Vec2 operator*(double s) const { return {x * s, y * s}; }
  double dot(Vec2 o) const { return x * o.x + y * o.y; }
  double cross(Vec2 o) const { return x * o.y - y * o.x; }
  double norm() const;
};

enum class Material : std::uint8_t { Facade, Car, Pole, Tree, Fence, Hedge };

/// How a surface returns radar power.
struct Surface {
  float reflectivity = 0.5f;      ///< relative backscatter, 0..1+
  float roughness = 0.5f;         ///< 0 = specular (strong only at normal incidence), 1 = diffuse
  float transmission = 0.0f;      ///< fraction of power passing through (0 = opaque)
  float depth_m = 0.3f;           ///< range extent of the return behind the surface
  float texture_period_m = 2.0f;  ///< along-surface texture cell (windows, pillars, branches)
  std::uint32_t texture_seed = 0;
  Material material = Material::Facade;
};

struct Segment {
  Vec2 a, b;
  Surface surface;
};

struct Circle {
  Vec2 centre;
  double radius = 0.2;
  Surface surface;
};

/// A vehicle driving back and forth along a straight street (a dynamic object).
struct Mover {
  Vec2 from, to;         ///< street centreline end points
  double lane_offset_m;  ///< to the left of the travel direction
  double speed_mps;
  double phase_m;  ///< position along the out-and-back cycle at t = 0
  double length_m, width_m;
};

struct WorldParams {
  int blocks_x = 5;  ///< city blocks west-east (streets = blocks + 1); valid [1, 50]
  int blocks_y = 4;  ///< city blocks south-north; valid [1, 50]
  double block_min_m = 85, block_max_m = 130;  ///< valid block_min_m [10, 1000], block_max_m [10, 1000]
  double street_half_width_min_m = 9,
         street_half_width_max_m = 13;   ///< centreline to facades; valid street_half_width_min_m [2, 100],
                                         ///< street_half_width_max_m [2, 100]
  double parked_car_probability = 0.55;  ///< per parking slot (redrawn per traversal); valid [0, 1]
  double pole_spacing_m = 32;            ///< valid [1, 10000]
  double tree_probability = 0.4;         ///< per street side: lined with trees; valid [0, 1]
  int moving_vehicles = 30;              ///< valid [0, 1000]
  double countryside_extent_m =
      550;  ///< how far the countryside loop reaches east of the city; valid [50, 10000]
  double corridor_facade_period_m =
      12;  ///< identical terraced houses along the corridor street; valid [1, 1000]
};

/// One hit of a ray on a surface.
struct RayHit {
  double range = 0;         ///< distance from the ray origin
  float cos_incidence = 1;  ///< |cos| of the angle between ray and surface normal
  float texture = 1;        ///< position-stable reflectivity modulation at the hit point
  const Surface* surface = nullptr;
  Vec2 normal;  ///< unit surface normal at the hit (facing the ray)
};

class World {
 public:
  WorldParams params;
  std::uint64_t seed = 0;
  std::vector<Segment> segments;
  std::vector<Circle> circles;
  std::vector<Mover> movers;
  std::vector<double> street_x, street_y;  ///< centrelines of the N-S and W-E streets
  std::vector<double> half_width_x, half_width_y;
  std::vector<Vec2> country_road;  ///< polyline from node(nx-1,1) to node(nx-1,ny-1)
  int corridor_row = 0;            ///< the W-E street lined with identical facades
  std::vector<Vec2> road_points;   ///< route worlds (route_world.h): centreline vertices (index bounds)

  Vec2 node(int i, int j) const { return {street_x.at(i), street_y.at(j)}; }
  int streetsX() const { return static_cast<int>(street_x.size()); }
  int streetsY() const { return static_cast<int>(street_y.size()); }

  /// Builds the spatial index; call after editing segments/circles.
  void buildIndex(double cell_m = 6.0);

  /// Segments of the moving vehicles at time t_s (seconds since the route start) within
  /// `radius` of `centre`, excluding any within `exclude_m` (the ego vehicle itself).
  void moverSegments(double t_s, Vec2 centre, double radius, double exclude_m,
                     std::vector<Segment>& out) const;

 private:
  friend class RayCaster;
  double x0_ = 0, y0_ = 0, cell_ = 6;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> cell_start_, cell_items_;  // CSR; item bit 31 set = circle
};

/// Casts rays through a World. Holds per-ray scratch (not thread-safe; one per thread).
class RayCaster {
 public:
  explicit RayCaster(const World& world);
  /// All hits along the ray (origin o, unit direction d) up to max_range, sorted by range,
  /// ending at the first opaque surface or when the transmitted fraction drops below 1e-3.
  /// `dynamic` are extra segments tested by brute force (moving vehicles).
  void cast(Vec2 o, Vec2 d, double max_range, const std::vector<Segment>& dynamic, std::vector<RayHit>& hits);

 private:
  const World& world_;
  std::vector<std::uint32_t> seg_mark_, circ_mark_;
  std::uint32_t ray_id_ = 0;
};

/// Generates the world for `seed`. `traversal` (1, 2, ...) changes only what changes between
/// drives through the same place: parked cars and moving vehicles.
World generateWorld(const WorldParams& params, std::uint64_t seed, int traversal);

}  // namespace radarslam::sim
