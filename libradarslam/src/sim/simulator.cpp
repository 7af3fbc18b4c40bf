#include "radarslam/sim/simulator.h"

#include <chrono>
#include <future>

#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/io/oxford_writer.h"
#include "radarslam/sim/gt_route.h"
#include "radarslam/sim/street_network.h"

namespace radarslam::sim {

WorldType parseWorldType(const std::string& name, const std::string& option) {
  if (name == "grid") return WorldType::Grid;
  if (name == "network") return WorldType::Network;
  if (name == "oxford-route") return WorldType::OxfordRoute;
  throw InputError(option, "unknown world '" + name + "' (grid, network, oxford-route)");
}

void loadSimulationConfig(const std::string& path, SimulationConfig& c) {
  requireRegularFile(path);
  const YamlParams y = YamlParams::fromFile(path);
  int seed = static_cast<int>(c.seed);
  y.get("seed", seed, Range::closed(0, 2147483647));
  c.seed = static_cast<std::uint64_t>(seed);
  y.get("traversal", c.traversal, Range::closed(1, 2));
  y.get("weather", c.weather);
  y.get("scans", c.scans, Range::closed(0, 100000));
  y.get("length_m", c.length_m, Range::closed(0, 100000.0));
  y.get("png_compression", c.png_compression, Range::closed(0, 9));
  y.get("world_type", c.world_type);
  y.get("scene", c.scene);
  y.get("route_from_gt", c.route_from_gt);
  const YamlParams w = y.section("world");
  w.get("blocks_x", c.world.blocks_x, Range::closed(1, 50));
  w.get("blocks_y", c.world.blocks_y, Range::closed(1, 50));
  w.get("block_min_m", c.world.block_min_m, Range::closed(10, 1000));
  w.get("block_max_m", c.world.block_max_m, Range::closed(10, 1000));
  w.get("street_half_width_min_m", c.world.street_half_width_min_m, Range::closed(2, 100));
  w.get("street_half_width_max_m", c.world.street_half_width_max_m, Range::closed(2, 100));
  w.get("parked_car_probability", c.world.parked_car_probability, Range::closed(0, 1));
  w.get("pole_spacing_m", c.world.pole_spacing_m, Range::closed(1, 10000.0));
  w.get("tree_probability", c.world.tree_probability, Range::closed(0, 1));
  w.get("moving_vehicles", c.world.moving_vehicles, Range::closed(0, 1000));
  w.get("countryside_extent_m", c.world.countryside_extent_m, Range::closed(50, 10000.0));
  w.get("corridor_facade_period_m", c.world.corridor_facade_period_m, Range::closed(1, 1000));
  const YamlParams rw = y.section("route_world");
  rw.get("margin_m", c.route_world.margin_m, Range::closed(0.1, 10));
  rw.get("scene_cell_m", c.route_world.scene_cell_m, Range::closed(20, 5000));
  rw.get("road_half_width_m", c.route_world.road_half_width_m, Range::closed(2, 30));
  rw.get("wall_length_m", c.route_world.wall_length_m, Range::closed(300, 400));
  const YamlParams r = y.section("route");
  r.get("lane_offset_m", c.route.lane_offset_m, Range::closed(-20, 20));
  r.get("lane_offset_traversal2_m", c.route.lane_offset_traversal2_m, Range::closed(-20, 20));
  r.get("city_speed_mps", c.route.city_speed_mps, Range::above(0, 15));
  r.get("corridor_speed_mps", c.route.corridor_speed_mps, Range::above(0, 15));
  r.get("country_speed_mps", c.route.country_speed_mps, Range::above(0, 15));
  r.get("lateral_accel_mps2", c.route.lateral_accel_mps2, Range::above(0, 20));
  r.get("curvature_transition_m", c.route.curvature_transition_m, Range::closed(0, 50));
  r.get("max_yaw_rate_dps", c.route.max_yaw_rate_dps, Range::above(0, 180));
  r.get("max_yaw_accel_dps2", c.route.max_yaw_accel_dps2, Range::above(0, 1000));
  r.get("accel_mps2", c.route.accel_mps2, Range::above(0, 20));
  r.get("decel_mps2", c.route.decel_mps2, Range::above(0, 20));
  r.get("stop_probability", c.route.stop_probability, Range::closed(0, 1));
  r.get("stop_min_s", c.route.stop_min_s, Range::closed(0, 600));
  r.get("stop_max_s", c.route.stop_max_s, Range::closed(0, 600));
  r.get("corner_radius_m", c.route.corner_radius_m, Range::closed(1, 100));
  r.get("country_corner_radius_m", c.route.country_corner_radius_m, Range::closed(1, 1000));
  r.get("start_time_s", c.route.start_time_s, Range::closed(0, 4000000000.0));
  r.get("traversal2_delay_s", c.route.traversal2_delay_s, Range::closed(0, 1000000000.0));
  loadGeometry(y.section("radar"), c.geometry);
  loadPhysics(y.section("physics"), c.physics);
  y.rejectUnknownKeys();
  if (c.world.block_max_m < c.world.block_min_m) w.fail("block_max_m", "must be >= block_min_m");
  if (c.world.street_half_width_max_m < c.world.street_half_width_min_m)
    w.fail("street_half_width_max_m", "must be >= street_half_width_min_m");
  if (c.route.stop_max_s < c.route.stop_min_s) r.fail("stop_max_s", "must be >= stop_min_s");
  try {
    parseWorldType(c.world_type, "world_type");
  } catch (const InputError&) {
    y.fail("world_type", "must be grid, network or oxford-route");
  }
  try {
    parseScene(c.scene, "scene");
  } catch (const InputError&) {
    y.fail("scene", "must be mixed, urban, suburban, country, carpark, avenue or wall");
  }
}

Simulation::Simulation(const SimulationConfig& config) : config_(config) {
  if (config.traversal < 1 || config.traversal > 2) throw InputError("--traversal", "must be 1 or 2");
  const WorldType type = parseWorldType(config.world_type);
  const Scene scene = parseScene(config.scene);
  const double period_s = 1.0 / config.geometry.rotation_hz;
  const double min_duration = config.scans > 0 ? (config.scans + 1) * period_s : 0.0;
  if (type == WorldType::Grid) {
    world_ = generateWorld(config.world, config.seed, config.traversal);
    route_ = planRoute(world_, config.route, config.seed, config.traversal, config.length_m, min_duration);
  } else if (type == WorldType::Network) {
    const StreetNetwork net = generateStreetNetwork(config.seed, config.route);
    world_ = generateRouteWorld(roadCentreline(net.lap, config.route), config.route_world, config.world,
                                scene, scene == Scene::Mixed ? net.zones : std::vector<SceneZone>{},
                                config.seed, config.traversal);
    route_ =
        planRouteThrough(net.lap, config.route, config.seed, config.traversal, config.length_m, min_duration);
  } else {
    if (config.route_from_gt.empty())
      throw InputError("--route-from-gt", "--world oxford-route needs the ground truth CSV to drive");
    if (config.length_m > 0) throw InputError("--length-m", "not with --world oxford-route (use --scans)");
    GroundTruthRoute g = routeFromOxfordGroundTruth(config.route_from_gt, config.route, config.traversal,
                                                    config.route_world.road_half_width_m);
    const std::vector<SceneZone> zones =
        scene == Scene::Mixed ? longStraightWallZones(g.roads, config.route_world.wall_length_m)
                              : std::vector<SceneZone>{};
    world_ = generateRouteWorld(g.roads, config.route_world, config.world, scene, zones, config.seed,
                                config.traversal);
    route_ = std::move(g.route);
    scan_starts_ = std::move(g.scan_starts);
    if (config.scans > 0 && static_cast<std::size_t>(config.scans) > scan_starts_.size())
      throw InputError("--scans",
                       "the ground-truth route has only " + std::to_string(scan_starts_.size()) + " scans");
  }
  if (!scan_starts_.empty())
    num_scans_ = config.scans > 0 ? static_cast<std::size_t>(config.scans) : scan_starts_.size();
  else
    num_scans_ = config.scans > 0
                     ? static_cast<std::size_t>(config.scans)
                     : static_cast<std::size_t>(std::max(0.0, route_.duration() / period_s - 1.0));
  renderer_ = std::make_unique<RadarRenderer>(
      world_, route_, config.geometry, config.physics, weatherPreset(config.weather),
      config.seed * 31 + static_cast<std::uint64_t>(config.traversal));
}

Simulation::~Simulation() = default;

StampNs Simulation::scanStart(std::size_t i) const {
  if (!scan_starts_.empty()) return scan_starts_.at(i);
  const StampNs period_us = config_.geometry.scanPeriodNs() / kNsPerUs;
  return route_.start_stamp + static_cast<StampNs>(i) * period_us * kNsPerUs;
}

void Simulation::render(std::size_t i, CObservationRadarScan& out) {
  renderer_->render(scanStart(i), i, out);
}

Trajectory Simulation::scanTruth() const {
  Trajectory t;
  CObservationRadarScan probe;
  for (std::size_t i = 0; i < num_scans_; ++i) {
    const StampNs first = renderer_->azimuthStamp(scanStart(i), 0);
    const StampNs last = renderer_->azimuthStamp(scanStart(i), config_.geometry.azimuths - 1);
    probe.azimuth_stamps_ns = {first, last};
    t.push_back({probe.refStampNs(), route_.poseAt(probe.refStampNs())});
  }
  return t;
}

SimulationSummary simulateToDirectory(const SimulationConfig& config, const std::filesystem::path& out_dir,
                                      const std::function<void(std::size_t, std::size_t)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(config);
  OxfordWriter writer(out_dir, config.png_compression, config.geometry.encoder_size);
  // Render scan i while scan i-1 is encoded and written on a second thread (double buffer).
  CObservationRadarScan buffers[2];
  std::future<void> pending;
  const std::size_t n = sim.numScans();
  for (std::size_t i = 0; i < n; ++i) {
    CObservationRadarScan& scan = buffers[i % 2];
    sim.render(i, scan);
    if (pending.valid()) pending.get();  // the previous write (rethrows its error)
    const auto truth = sim.truthAt(scan.refStampNs());
    pending = std::async(std::launch::async, [&writer, &scan, truth] { writer.writeScan(scan, truth); });
    if (progress) progress(i + 1, n);
  }
  if (pending.valid()) pending.get();
  writer.finish();
  SimulationSummary s;
  s.scans = n;
  const Trajectory truth = sim.scanTruth();
  s.length_m = pathLength(truth);
  for (const auto& e : findLoops(truth)) {
    ++s.loops;
    if (e.opposite_direction) ++s.opposite_loops;
  }
  s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

}  // namespace radarslam::sim
