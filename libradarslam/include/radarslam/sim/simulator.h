#pragma once
// The simulator as one object: world + route + radar for a seed, traversal and weather, and the
// loop that renders a sequence scan by scan into an Oxford-format directory.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "radarslam/sim/radar_model.h"
#include "radarslam/sim/route.h"
#include "radarslam/sim/route_world.h"
#include "radarslam/sim/world.h"

namespace radarslam::sim {

/// grid: the procedural city and countryside (world.h, the default); network: an irregular street
/// network (street_network.h); oxford-route: the route of a real Oxford ground truth (gt_route.h).
/// The last two generate their world around the route (route_world.h).
enum class WorldType { Grid, Network, OxfordRoute };

/// "grid", "network", "oxford-route" -> WorldType; anything else is an InputError naming `option`.
WorldType parseWorldType(const std::string& name, const std::string& option = "--world");

struct SimulationConfig {
  std::uint64_t seed = 1;         ///< valid [0, 2147483647]
  int traversal = 1;              ///< 2 = a second drive through the same world; valid [1, 2]
  std::string weather = "clear";  ///< clear, fog, rain, snow
  int scans = 0;                  ///< > 0: exactly this many scans; valid [0, 100000]
  double length_m = 0;      ///< > 0: route length (0 and scans 0: the full demo tour); valid [0, 100000]
  int png_compression = 1;  ///< valid [0, 9]
  std::string world_type = "grid";  ///< grid, network, oxford-route
  std::string scene =
      "mixed";  ///< network/oxford-route: mixed, urban, suburban, country, carpark, avenue, wall
  std::string route_from_gt = "";  ///< oxford-route: an Oxford gt/radar_odometry.csv (never copied)
  WorldParams world;
  RouteWorldParams route_world;
  RouteParams route;
  RadarGeometry geometry;
  RadarPhysics physics;
};

/// Overrides `config` from a YAML file with sections world, route_world, route, radar, physics and
/// top-level keys seed, traversal, weather, scans, length_m, png_compression, world_type, scene,
/// route_from_gt. Unknown keys are errors.
void loadSimulationConfig(const std::string& path, SimulationConfig& config);

class Simulation {
 public:
  explicit Simulation(const SimulationConfig& config);
  ~Simulation();

  const World& world() const { return world_; }
  const Route& route() const { return route_; }
  std::size_t numScans() const { return num_scans_; }
  /// First-azimuth stamp of scan i.
  StampNs scanStart(std::size_t i) const;
  /// Renders scan i (fresh speckle per scan, reproducible).
  void render(std::size_t i, CObservationRadarScan& out);
  /// True radar pose at a stamp.
  mrpt::math::TPose2D truthAt(StampNs t) const { return route_.poseAt(t); }
  /// Truth at every scan's reference (mid-sweep) time.
  Trajectory scanTruth() const;

 private:
  SimulationConfig config_;
  World world_;
  Route route_;
  std::size_t num_scans_ = 0;
  std::vector<StampNs> scan_starts_;  ///< oxford-route: the real scan times (else a fixed period)
  std::unique_ptr<RadarRenderer> renderer_;
};

struct SimulationSummary {
  std::size_t scans = 0;
  double length_m = 0;  ///< distance driven during the scans
  std::size_t loops = 0, opposite_loops = 0;
  double wall_seconds = 0;
};

/// Renders the whole sequence into `out_dir` (Oxford layout, see io/oxford_writer.h).
/// `progress(done, total)` is called after every scan.
SimulationSummary simulateToDirectory(const SimulationConfig& config, const std::filesystem::path& out_dir,
                                      const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace radarslam::sim
