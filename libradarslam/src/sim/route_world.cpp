// The world around a route (route_world.h). Each scene is a set of "rows": lines parallel to the
// road at an offset from its edge (facades, kerb furniture, parking, hedges, ...). A row's line is
// cut where it crosses the cells of a lattice fixed in the world; each piece (one lattice cell,
// one side of the road, one direction class) is generated once, from a generator seeded by that
// key and with its points in a canonical order, so the objects depend on where they are, not on
// when or in which direction the route passes. Every object is then trimmed to stay clear of
// every road piece by the margin.
#include "radarslam/sim/route_world.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "clear_placer.h"
#include "radarslam/core/errors.h"
#include "radarslam/sim/rng.h"
#include "world_builder.h"

namespace radarslam::sim {

using namespace detail;

namespace {

constexpr Scene kScenes[] = {Scene::Mixed,   Scene::Urban,  Scene::Suburban, Scene::Country,
                             Scene::Carpark, Scene::Avenue, Scene::Wall};
constexpr const char* kSceneNames[] = {"mixed", "urban", "suburban", "country", "carpark", "avenue", "wall"};

enum class Row : std::uint8_t {
  Facade,
  Kerb,
  Parking,
  Garden,
  House,
  Hedgerow,
  Barrier,
  Field,
  Carpark,
  Trees,
  Wall
};

struct RowSpec {
  Row row;
  double offset_m;   // from the road's edge to the row's line
  double lattice_m;  // piece size
};

std::vector<RowSpec> rowsOf(Scene s) {
  switch (s) {
    case Scene::Urban:
      return {{Row::Facade, 2.5, 22}, {Row::Kerb, 1.0, 30}, {Row::Parking, 1.4, 24}};
    case Scene::Suburban:
      return {{Row::Garden, 3.5, 25}, {Row::House, 10, 25}, {Row::Kerb, 1.0, 30}, {Row::Parking, 1.4, 24}};
    case Scene::Country:
      return {{Row::Hedgerow, 3.0, 30}, {Row::Barrier, 0.8, 40}, {Row::Field, 5.0, 30}};
    case Scene::Carpark:
      return {{Row::Carpark, 4.0, 30}, {Row::Kerb, 1.0, 30}};
    case Scene::Avenue:
      return {{Row::Trees, 1.8, 27}, {Row::Facade, 7.0, 22}, {Row::Kerb, 1.0, 30}};
    case Scene::Wall:
      return {{Row::Wall, 1.5, 25}};
    case Scene::Mixed:
      break;
  }
  return {};
}

std::uint64_t hashAll(std::initializer_list<std::uint64_t> v) {
  std::uint64_t h = 0x5EED;
  for (auto x : v) h = hashCombine(h, x);
  return h;
}

std::uint64_t cellKey(double v, double size) {
  return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / size)));
}

/// Where a piece came from: its row, scene, side and the lattice cell it lies in.
struct Piece {
  std::vector<Vec2> pts;  // canonical order: along the canonical direction
  Vec2 road_mid;          // the centreline point opposite the middle of the piece
  Vec2 dir, out;          // canonical direction (chord), outward normal (away from the road)
  double length = 0;
  std::uint64_t key = 0;
};

class RouteWorldBuilder {
 public:
  RouteWorldBuilder(World& w, const std::vector<RoadPiece>& roads, const RouteWorldParams& p, Scene scene,
                    const std::vector<SceneZone>& zones, int traversal)
      : w_(w), place_(w, roads, p.margin_m), p_(p), scene_(scene), zones_(zones), traversal_(traversal) {}

  /// The scene at p and the zone index (-1 = none).
  Scene sceneAt(Vec2 q, int& zone) const {
    for (std::size_t k = 0; k < zones_.size(); ++k)
      if (distanceToSegment(q, zones_[k].a, zones_[k].b) < zones_[k].radius_m) {
        zone = static_cast<int>(k);
        return zones_[k].scene;
      }
    zone = -1;
    if (scene_ != Scene::Mixed) return scene_;
    const double u =
        hashToUnit(hashAll({w_.seed, 11, cellKey(q.x, p_.scene_cell_m), cellKey(q.y, p_.scene_cell_m)}));
    // The long wall only where a zone puts it: one mixed cell is shorter than the 300-400 m wall.
    if (u < 0.30) return Scene::Urban;
    if (u < 0.52) return Scene::Suburban;
    if (u < 0.74) return Scene::Country;
    if (u < 0.84) return Scene::Carpark;
    return Scene::Avenue;
  }

  void generate(const std::vector<std::vector<RoadPiece>>& chains) {
    for (const auto& chain : chains)
      for (int side = -1; side <= 1; side += 2)
        for (Scene s : kScenes)
          for (const RowSpec& spec : rowsOf(s)) rowAlong(chain, side, s, spec);
  }

 private:
  /// The row's line on one side of a chain of pieces, cut exactly where it crosses the lattice
  /// (cells of lattice_m fixed in the world). Every step is symmetric under reversing the chain
  /// (and swapping the side), so both directions of a street give the same pieces, bit for bit.
  void rowAlong(const std::vector<RoadPiece>& chain, int side, Scene scene, const RowSpec& spec) {
    std::vector<Vec2> line, road;  // the row's line and the centreline points it is offset from
    for (std::size_t k = 0; k <= chain.size(); ++k) {
      const RoadPiece& before = chain[k == 0 ? 0 : k - 1];
      const RoadPiece& after = chain[std::min(k, chain.size() - 1)];
      const Vec2 p = k < chain.size() ? after.a : before.b;
      const double hw = std::max(before.half_width, after.half_width);
      road.push_back(p);
      line.push_back(p + leftOf(unit(unit(before.b - before.a) + unit(after.b - after.a))) *
                             (side * (hw + spec.offset_m)));
    }
    const double L = spec.lattice_m;
    std::vector<Vec2> cur{line.front()}, cur_road{road.front()};
    std::vector<std::pair<double, Vec2>> at;
    for (std::size_t k = 1; k < line.size(); ++k) {
      const bool swap =
          line[k].x < line[k - 1].x || (line[k].x == line[k - 1].x && line[k].y < line[k - 1].y);
      const Vec2 u = swap ? line[k] : line[k - 1], v = swap ? line[k - 1] : line[k];
      const Vec2 ru = swap ? road[k] : road[k - 1], rv = swap ? road[k - 1] : road[k];
      at.clear();
      for (int axis = 0; axis < 2; ++axis) {
        const double a = axis == 0 ? u.x : u.y, b = axis == 0 ? v.x : v.y;
        if (a == b) continue;
        for (double g = std::floor(std::min(a, b) / L) + 1; g * L < std::max(a, b); ++g) {
          const double t = (g * L - a) / (b - a);
          Vec2 q = u + (v - u) * t;
          (axis == 0 ? q.x : q.y) = g * L;
          at.push_back({t, q});
        }
      }
      std::sort(at.begin(), at.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      if (swap) std::reverse(at.begin(), at.end());
      for (const auto& [t, c] : at) {
        const Vec2 rc = ru + (rv - ru) * t;
        cur.push_back(c), cur_road.push_back(rc);
        emitPiece(cur, cur_road, side, scene, spec);
        cur = {c}, cur_road = {rc};
      }
      cur.push_back(line[k]), cur_road.push_back(road[k]);
    }
    emitPiece(cur, cur_road, side, scene, spec);
  }

  void emitPiece(std::vector<Vec2> pts, std::vector<Vec2> road, int side, Scene scene, const RowSpec& spec) {
    if (pts.size() < 2) return;
    Vec2 d = pts.back() - pts.front();
    const double len = d.norm();
    if (len < 0.5) return;
    d = d * (1.0 / len);
    Vec2 out = leftOf(d) * static_cast<double>(side);
    if (d.x < 0 || (d.x == 0 && d.y < 0)) {  // canonical order: the same for both directions
      std::reverse(pts.begin(), pts.end());
      std::reverse(road.begin(), road.end());
      d = d * -1.0;
    }
    int zone = -1;
    if (sceneAt(pts[pts.size() / 2], zone) != scene) return;
    std::size_t first = 1;  // the cell: of the first sub-segment of non-zero length
    while (first + 1 < pts.size() && (pts[first] - pts[first - 1]).norm() < 1e-9) ++first;
    const Vec2 inside = (pts[first] + pts[first - 1]) * 0.5;
    const std::pair cell{cellKey(inside.x, spec.lattice_m), cellKey(inside.y, spec.lattice_m)};
    const double angle = std::atan2(d.y, d.x);  // in (-pi/2, pi/2]
    const auto dir_class = static_cast<std::uint64_t>(std::floor((angle + M_PI / 2) / (M_PI / 6)));
    const bool left = leftOf(d).dot(out) > 0;
    Piece piece{pts,
                road[road.size() / 2],
                d,
                out,
                len,
                hashAll({w_.seed, static_cast<std::uint64_t>(spec.row), cell.first, cell.second, dir_class,
                         left ? 1u : 2u, static_cast<std::uint64_t>(scene)})};
    if (!done_.insert(piece.key).second) return;  // this place was generated by an earlier pass
    Rng rng(piece.key);
    Rng traversal_rng(hashCombine(piece.key, static_cast<std::uint64_t>(traversal_)));
    switch (spec.row) {
      case Row::Facade:
        facades(piece, rng);
        break;
      case Row::Kerb:
        kerb(piece, rng);
        break;
      case Row::Parking:
        parking(piece, traversal_rng);
        break;
      case Row::Garden:
        garden(piece, rng);
        break;
      case Row::House:
        house(piece, rng);
        break;
      case Row::Hedgerow:
        hedgerow(piece, rng);
        break;
      case Row::Barrier:
        barrier(piece, rng);
        break;
      case Row::Field:
        field(piece, rng);
        break;
      case Row::Carpark:
        carpark(piece, rng, traversal_rng);
        break;
      case Row::Trees:
        avenueTrees(piece, rng);
        break;
      case Row::Wall:
        wall(piece, zone);
        break;
    }
  }

  Vec2 at(const Piece& p, double u, double offset) const {
    return p.pts.front() + p.dir * u + p.out * offset;
  }

  void car(const Piece& p, double u, double offset, Vec2 dir, Rng& trng) {
    const Vec2 c = at(p, u + trng.uniform(-0.3, 0.3), offset + trng.uniform(-0.15, 0.15));
    const double length = trng.uniform(4.0, 4.9), width = trng.uniform(1.7, 2.0);
    place_.box(c, dir, length, width, carSurface(trng), true);
  }

  // --- rows --------------------------------------------------------------------------------------
  /// Urban buildings (8-30 m boxes along the road, setbacks, alleys); in a terrace cell, identical
  /// houses of one surface for the whole world (look-alike places).
  void facades(const Piece& p, Rng& rng) {
    const bool terrace = hashToUnit(hashAll({w_.seed, 12, cellKey(p.pts.front().x, 2 * p_.scene_cell_m / 3),
                                             cellKey(p.pts.front().y, 2 * p_.scene_cell_m / 3)})) < 0.3;
    if (terrace) {
      Rng trng(hashCombine(w_.seed, 0x7E77ACE));
      Surface s = facadeSurface(trng);
      s.texture_period_m = 2.0f;
      constexpr double period = 11.0;
      const double first = std::fmod(p.pts.front().dot(p.dir), period);  // houses on a world lattice
      for (double u = period - (first < 0 ? first + period : first); u + period <= p.length; u += period) {
        place_.segment(at(p, u, 0), at(p, u + period, 0), s);
        place_.segment(at(p, u, 0), at(p, u, 10), s);
      }
      return;
    }
    if (p.length < 8 || rng.chance(0.15)) return;  // an alley, a gap, a short remnant
    const double setback = rng.uniform(0.0, 1.5);
    const double trim0 = rng.chance(0.5) ? 0.0 : rng.uniform(0.5, 2.0);
    const double trim1 = rng.chance(0.5) ? 0.0 : rng.uniform(0.5, 2.0);
    const double len = p.length - trim0 - trim1, depth = rng.uniform(8, 20);
    place_.box(at(p, trim0 + len / 2, setback + depth / 2), p.dir, len, depth, facadeSurface(rng), false);
  }

  void kerb(const Piece& p, Rng& rng) {
    if (rng.chance(0.8)) place_.pole(at(p, rng.uniform(0, p.length), 0), rng);
    for (double u = rng.uniform(0, 6); u < p.length; u += rng.uniform(3, 9))
      place_.clutter(at(p, u, rng.uniform(0.0, 2.5)), rng);
  }

  void parking(const Piece& p, Rng& trng) {
    for (double u = 3; u < p.length - 2.5; u += 6.0)
      if (trng.chance(w_.params.parked_car_probability)) car(p, u, 0, p.dir, trng);
  }

  void garden(const Piece& p, Rng& rng) {
    if (rng.chance(0.2)) return;
    const double gap0 = rng.uniform(0.0, 4.0), gap1 = rng.uniform(0.0, 1.0);  // a driveway
    const Surface s = rng.chance(0.6) ? hedgeSurface(rng) : fenceSurface(rng);
    place_.segment(at(p, gap0, 0), at(p, std::max(gap0, p.length - gap1), 0), s);
    if (rng.chance(0.4)) place_.tree(at(p, rng.uniform(0, p.length), rng.uniform(3, 6)), rng);
  }

  void house(const Piece& p, Rng& rng) {
    if (p.length < 10 || rng.chance(0.15)) return;
    const double width = std::min(p.length - 1, rng.uniform(9, 14)), depth = rng.uniform(8, 12);
    const double u = rng.uniform(width / 2, p.length - width / 2);
    place_.box(at(p, u, rng.uniform(0, 5) + depth / 2), p.dir, width, depth, facadeSurface(rng), false);
  }

  void hedgerow(const Piece& p, Rng& rng) {
    if (rng.chance(0.4)) return;  // a gap (a gate, a field entrance)
    const double a = rng.uniform(0, 0.3 * p.length), b = rng.uniform(0.7 * p.length, p.length);
    place_.segment(at(p, a, rng.uniform(-1, 1)), at(p, b, rng.uniform(-1, 1)), hedgeSurface(rng));
  }

  /// A metal crash barrier along a dual carriageway (cells of that kind only), no gaps.
  void barrier(const Piece& p, Rng& rng) {
    const bool dual = hashToUnit(hashAll({w_.seed, 13, cellKey(p.pts.front().x, p_.scene_cell_m),
                                          cellKey(p.pts.front().y, p_.scene_cell_m)})) < 0.4;
    if (!dual) return;
    Surface s = fenceSurface(rng);
    s.reflectivity = 0.9f;
    s.roughness = 0.25f;
    s.transmission = 0.5f;  // low: the fan beam sees over it
    s.texture_period_m = 4.0f;
    for (std::size_t k = 1; k < p.pts.size(); ++k) place_.segment(p.pts[k - 1], p.pts[k], s);
  }

  void field(const Piece& p, Rng& rng) {
    if (rng.chance(0.3)) place_.tree(at(p, rng.uniform(0, p.length), rng.uniform(0, 25)), rng);
    if (rng.chance(0.5)) place_.pole(at(p, rng.uniform(0, p.length), -2.5), rng);
    for (int k = 0; k < 3; ++k) place_.clutter(at(p, rng.uniform(0, p.length), rng.uniform(5, 120)), rng);
    if (rng.chance(0.06)) {  // a farm building
      const double w = rng.uniform(15, 30), d = rng.uniform(8, 14);
      place_.box(at(p, p.length / 2, rng.uniform(30, 70)), p.dir, w, d, facadeSurface(rng), false);
    }
  }

  /// Rows of cars parked across the direction of the road, lamp posts between them, a fence on
  /// the sides without a car park.
  void carpark(const Piece& p, Rng& rng, Rng& trng) {
    const bool lot = hashToUnit(hashAll({w_.seed, 14, cellKey(p.pts.front().x, p_.scene_cell_m),
                                         cellKey(p.pts.front().y, p_.scene_cell_m), p.out.x > 0})) < 0.7;
    if (!lot) {
      place_.segment(at(p, 0, -2), at(p, p.length, -2), fenceSurface(rng));
      return;
    }
    const Vec2 across = p.out;
    for (int row = 0; row < 5; ++row) {
      const double offset = 2.5 + row * 7.0;
      for (double u = 1.3; u < p.length - 1.3; u += 2.6)
        if (trng.chance(w_.params.parked_car_probability)) car(p, u, offset, across, trng);
      if (row % 2 == 1) place_.pole(at(p, rng.uniform(0, p.length), offset + 3.5), rng);
    }
  }

  void avenueTrees(const Piece& p, Rng& rng) {
    for (double u = rng.uniform(1, 4); u < p.length; u += rng.uniform(8, 10)) place_.tree(at(p, u, 0), rng);
  }

  /// One smooth facade following the road on one side only (per zone, or per wall-length cell).
  void wall(const Piece& p, int zone) {
    const Vec2 mid = p.road_mid;  // the same for both sides of the road
    const std::uint64_t id =
        zone >= 0
            ? hashAll({w_.seed, 15, static_cast<std::uint64_t>(zone)})
            : hashAll({w_.seed, 16, cellKey(mid.x, p_.wall_length_m), cellKey(mid.y, p_.wall_length_m)});
    const bool left_side = hashToUnit(id) < 0.5;
    if ((leftOf(p.dir).dot(p.out) > 0) != left_side) return;
    Surface s;
    s.material = Material::Facade;
    s.reflectivity = 0.6f;
    s.roughness = 0.05f;  // smooth: bright only at normal incidence
    s.transmission = 0.0f;
    s.depth_m = 0.1f;
    s.texture_period_m = 1.0e4f;  // no windows, no pillars
    s.texture_seed = static_cast<std::uint32_t>(w_.seed * 2654435761u + 0x3A11u);
    for (std::size_t k = 1; k < p.pts.size(); ++k) place_.segment(p.pts[k - 1], p.pts[k], s);
  }

  World& w_;
  ClearPlacer place_;
  const RouteWorldParams& p_;
  Scene scene_;
  const std::vector<SceneZone>& zones_;
  int traversal_;
  std::unordered_set<std::uint64_t> done_;
};

/// Consecutive pieces that join (b == a) as chains, split where the road turns back on itself
/// (a turn of more than 120 degrees: the row lines would fold over).
std::vector<std::vector<RoadPiece>> chainsOf(const std::vector<RoadPiece>& roads) {
  std::vector<std::vector<RoadPiece>> chains;
  for (const RoadPiece& r : roads) {
    if ((r.b - r.a).norm() < 1e-6) continue;
    const bool joins = !chains.empty() && (chains.back().back().b - r.a).norm() <= 1e-6 &&
                       unit(chains.back().back().b - chains.back().back().a).dot(unit(r.b - r.a)) > -0.5;
    if (!joins) chains.emplace_back();
    chains.back().push_back(r);
  }
  return chains;
}

/// Moving vehicles back and forth on straight stretches (>= 50 m, heading within 4 degrees).
void addTraffic(World& w, const std::vector<std::vector<RoadPiece>>& chains, Rng& trng) {
  struct Stretch {
    Vec2 a, b;
    double hw;
  };
  std::vector<Stretch> straight;
  for (const auto& chain : chains) {
    std::size_t start = 0;
    for (std::size_t k = 1; k <= chain.size(); ++k) {
      const Vec2 d0 = unit(chain[start].b - chain[start].a);
      const bool bends = k < chain.size() && unit(chain[k].b - chain[k].a).dot(d0) < std::cos(4 * M_PI / 180);
      if (k == chain.size() || bends) {
        if ((chain[k - 1].b - chain[start].a).norm() >= 50)
          straight.push_back({chain[start].a, chain[k - 1].b, chain[start].half_width});
        start = k;
      }
    }
  }
  for (int k = 0; k < w.params.moving_vehicles && !straight.empty(); ++k) {
    const Stretch& s = straight[trng.below(static_cast<std::uint32_t>(straight.size()))];
    const bool big = trng.chance(0.2);  // buses and lorries: long, occluding
    w.movers.push_back({s.a, s.b, s.hw * trng.uniform(0.35, 0.65), trng.uniform(4, 13), trng.uniform(0, 1000),
                        big ? trng.uniform(10, 12) : trng.uniform(4.2, 4.8),
                        big ? 2.5 : trng.uniform(1.7, 1.9)});
  }
}

}  // namespace

Scene parseScene(const std::string& name, const std::string& option) {
  for (std::size_t k = 0; k < std::size(kScenes); ++k)
    if (name == kSceneNames[k]) return kScenes[k];
  throw InputError(option,
                   "unknown scene '" + name + "' (mixed, urban, suburban, country, carpark, avenue, wall)");
}

const char* sceneName(Scene s) { return kSceneNames[static_cast<int>(s)]; }

std::vector<SceneZone> longStraightWallZones(const std::vector<RoadPiece>& roads, double length_m) {
  for (const auto& chain : chainsOf(roads)) {
    for (std::size_t i = 0; i < chain.size(); ++i) {
      double s = 0;
      std::size_t j = i;
      while (j < chain.size() && s < length_m) s += (chain[j].b - chain[j].a).norm(), ++j;
      if (s < length_m) break;
      const Vec2 a = chain[i].a, b = chain[j - 1].b;
      bool straight = true;
      for (std::size_t k = i; k < j && straight; ++k) straight = distanceToSegment(chain[k].b, a, b) <= 6.0;
      const Vec2 d = unit(b - a);  // the zone reaches 30 m beyond its axis: shorten the axis by as much
      if (straight) return {{a + d * 30.0, b - d * 30.0, 30, Scene::Wall}};
    }
  }
  return {};
}

World generateRouteWorld(const std::vector<RoadPiece>& roads, const RouteWorldParams& params,
                         const WorldParams& world_params, Scene scene, const std::vector<SceneZone>& zones,
                         std::uint64_t seed, int traversal) {
  World w;
  w.params = world_params;
  w.seed = seed;
  const auto chains = chainsOf(roads);
  RouteWorldBuilder(w, roads, params, scene, zones, traversal).generate(chains);
  Rng trng(hashCombine(hashCombine(seed, 22), static_cast<std::uint64_t>(traversal)));
  addTraffic(w, chains, trng);
  for (const RoadPiece& r : roads) w.road_points.push_back(r.a), w.road_points.push_back(r.b);
  w.buildIndex();
  return w;
}

}  // namespace radarslam::sim
