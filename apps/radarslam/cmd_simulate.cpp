// radarslam simulate: renders a realistic radar sequence of a procedural world in the Oxford
// Radar RobotCar format (see docs/simulator.md), or compares simulated scans with real ones.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/cleanup_on_signal.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/output_path.h>
#include <radarslam/io/dataset.h>
#include <radarslam/radar/cartesian.h>
#include <radarslam/sim/realism_statistics.h>
#include <radarslam/sim/scan_statistics.h>
#include <radarslam/sim/simulator.h>
#include <radarslam/sim/streak_statistics.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli_common.h"
#include "command.h"
#include "progress_line.h"

namespace fs = std::filesystem;
using namespace radarslam;

namespace {

cv::Mat labelled(const cv::Mat& img, const std::string& text) {
  cv::Mat out;
  cv::cvtColor(img, out, cv::COLOR_GRAY2BGR);
  cv::putText(out, text, {8, 22}, cv::FONT_HERSHEY_SIMPLEX, 0.6, {80, 220, 255}, 1, cv::LINE_AA);
  return out;
}

/// Real vs simulated: intensity statistics on stdout and a side-by-side Cartesian PNG.
int compareReal(const fs::path& real_dir, const fs::path& out_png, sim::SimulationConfig config) {
  const auto reader = openDataset(real_dir);
  if (reader->size() == 0) throw InputError(real_dir.string(), "no scans");
  std::vector<sim::ScanStatistics> real_stats, sim_stats;
  std::vector<sim::RealismStatistics> real_bands, sim_bands;
  std::vector<sim::StreakFractions> real_streaks, sim_streaks;
  CObservationRadarScan::Ptr first_real;
  for (std::size_t i = 0; i < reader->size(); ++i) {
    const auto scan = reader->readScan(i);
    if (!first_real) first_real = scan;
    real_stats.push_back(sim::computeScanStatistics(*scan));
    real_bands.push_back(sim::computeRealismStatistics(*scan));
    real_streaks.push_back(sim::computeStreakFractions(*scan));
  }
  // Same geometry as the real sensor; scans from the moving part of the city route.
  config.geometry.azimuths = static_cast<int>(first_real->num_azimuths);
  config.geometry.bins = static_cast<int>(first_real->num_bins);
  config.geometry.range_resolution_m = first_real->range_resolution_m;
  const std::size_t first = 60, count = reader->size();
  config.scans = static_cast<int>(first + count);
  sim::Simulation simulation(config);
  CObservationRadarScan sim_scan, shown;
  for (std::size_t i = first; i < first + count; ++i) {
    simulation.render(i, sim_scan);
    if (i == first) shown = sim_scan;
    sim_stats.push_back(sim::computeScanStatistics(sim_scan));
    sim_bands.push_back(sim::computeRealismStatistics(sim_scan));
    sim_streaks.push_back(sim::computeStreakFractions(sim_scan));
  }
  const auto real = sim::averageStatistics(real_stats), simulated = sim::averageStatistics(sim_stats);
  std::cout << "real: " << real_dir.string() << " (" << count << " scans)   simulated: seed " << config.seed
            << ", " << count << " scans\n"
            << sim::compareStatisticsTable(real, simulated)
            << "\nper range band (docs/simulator.md, Realism):\n"
            << sim::compareRealism(sim::averageRealism(real_bands), sim::averageRealism(sim_bands)).table;
  // Not in the count above (docs/simulator.md, "Saturation streaks"): shown, not yet calibrated.
  const sim::StreakFractions real_streak = sim::averageStreaks(real_streaks);
  const sim::StreakFractions sim_streak = sim::averageStreaks(sim_streaks);
  std::cout << "saturation streaks (azimuths whose median over 20-160 m exceeds their neighbours', % of "
               "azimuths):\n";
  for (std::size_t t = 0; t < sim::kStreakThresholdsCodes.size(); ++t)
    std::printf("  >= %2d codes   real %5.2f %%   sim %5.2f %%\n", sim::kStreakThresholdsCodes[t],
                100 * real_streak.fraction[t], 100 * sim_streak.fraction[t]);
  std::fflush(stdout);
  PolarToCartesian cart(CartesianParams{.size_px = 400, .m_per_px = 0.4});
  cv::Mat side;
  cv::hconcat(labelled(cart.convert(*first_real), "real (" + toString(reader->kind()) + ")"),
              labelled(cart.convert(shown), "simulated"), side);
  std::vector<unsigned char> bytes;
  cv::imencode(".png", side, bytes, {cv::IMWRITE_PNG_COMPRESSION, 9});
  writeBytesAtomically(out_png, bytes);
  std::cout << "wrote " << out_png.string() << " (" << bytes.size() / 1024 << " KB)\n";
  return 0;
}

/// True if `dir` holds nothing but what a simulation writes (radar/*.png, radar.timestamps, radar.geometry,
/// gt/radar_odometry.csv, gt/poses.tum, hidden temporaries): only such a directory is replaced.
bool onlySimulationOutput(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if ((name == "radar.timestamps" || name == "radar.geometry") && e.is_regular_file(ec)) continue;
    if ((name == "radar" || name == "gt") && e.is_directory(ec) && !e.is_symlink(ec)) {
      for (const auto& f : fs::directory_iterator(e.path(), ec)) {
        const std::string n = f.path().filename().string();
        const bool ours = name == "radar" ? f.path().extension() == ".png" || n.front() == '.'
                                          : n == "radar_odometry.csv" || n == "poses.tum" || n.front() == '.';
        if (!ours || !f.is_regular_file(ec)) return false;
      }
      continue;
    }
    return false;
  }
  return !ec;
}

/// Checks OUT_DIR before any work: missing, empty, or (with --force) a previous simulation.
void checkSimulationOutput(const std::string& out, bool force) {
  checkDirectoryOutput(out, "OUT_DIR");
  const fs::path dir = followSymlinks(out);
  std::error_code ec;
  if (!fs::exists(dir, ec) || fs::is_empty(dir, ec)) return;
  if (!onlySimulationOutput(dir))
    throw InputError(out, "is not empty and holds more than a previous simulation: refusing to replace it");
  if (!force)
    throw InputError(out, "output directory is not empty (use --force to replace a previous simulation)");
}

/// Moves the finished simulation in `staging` to `dir`, replacing a previous one there.
void publishSimulation(const fs::path& staging, const fs::path& dir) {
  std::error_code ec;
  const fs::path old = stagingSibling(dir, "sim-old");
  const bool had_old = fs::exists(dir, ec) && !fs::is_empty(dir, ec);
  if (had_old) {
    fs::rename(dir, old, ec);
    if (ec) throw InputError(dir.string(), "cannot move the previous simulation aside: " + ec.message());
  }
  fs::rename(staging, dir, ec);  // also over an empty directory
  if (ec) {
    const std::string msg = ec.message();
    if (had_old) fs::rename(old, dir, ec);
    throw InputError(dir.string(), "cannot move the simulation into place: " + msg);
  }
  if (had_old) fs::remove_all(old, ec);
}

int runSimulate(int argc, char** argv) {
  cli::CommandLine cmd(
      "simulate",
      "Simulate a Navtech-like 360-degree radar driving through a procedural city and countryside; "
      "writes an Oxford Radar RobotCar-format sequence (radar/*.png, radar.timestamps, "
      "gt/radar_odometry.csv, gt/poses.tum). Default: the >= 3 km demo route in clear weather; "
      "--world network / oxford-route for worlds generated around other routes.");
  auto& c = cmd.tclap();
  TCLAP::UnlabeledValueArg<std::string> out(
      "OUT_DIR", "Output directory (with --compare-real: the output PNG)", true, "", "OUT_DIR", c);
  TCLAP::ValueArg<std::string> compare(
      "", "compare-real",
      "Compare simulated scans with the real scans in DIR (any dataset the readers accept; the "
      "simulation takes its sensor geometry): print intensity statistics and write a side-by-side "
      "Cartesian PNG to OUT_DIR",
      false, "", "DIR", c);
  TCLAP::SwitchArg force(
      "", "force",
      "Replace a previous simulation in OUT_DIR (a directory holding anything else is never replaced)", c);
  TCLAP::ValueArg<double> rpm("", "rpm", "Rotation rate, revolutions per minute (default 240 = 4 Hz)", false,
                              0, "RPM", c);
  TCLAP::ValueArg<double> resolution("", "resolution", "Range resolution, m/bin (default 0.0432)", false, 0,
                                     "M", c);
  TCLAP::ValueArg<int> bins("", "bins", "Range bins (default 3768)", false, 0, "N", c);
  TCLAP::ValueArg<int> azimuths("", "azimuths", "Azimuths per rotation (default 400)", false, 0, "N", c);
  TCLAP::ValueArg<std::string> config_file("", "config", "Simulator parameters (YAML, e.g. config/sim.yaml)",
                                           false, "", "FILE", c);
  TCLAP::ValueArg<std::string> weather("", "weather", "clear, fog, rain or snow", false, "", "NAME", c);
  TCLAP::ValueArg<int> traversal("", "traversal", "1, or 2 for a second drive through the same world", false,
                                 0, "1|2", c);
  TCLAP::ValueArg<double> length("", "length-m", "Route length in metres", false, 0, "L", c);
  TCLAP::ValueArg<int> scans("", "scans", "Number of scans", false, 0, "N", c);
  TCLAP::ValueArg<int> seed("", "seed", "World/route/noise seed (default 1)", false, -1, "N", c);
  TCLAP::ValueArg<std::string> world(
      "", "world",
      "grid (default: the procedural city grid and countryside loop), network (an irregular street "
      "network: curves, a roundabout, a cul-de-sac U-turn, a loop driven both ways) or oxford-route "
      "(the real route and timing of --route-from-gt); network and oxford-route generate the world "
      "around the route",
      false, "", "grid|network|oxford-route", c);
  TCLAP::ValueArg<std::string> scene(
      "", "scene",
      "Scene beside the road for network/oxford-route: mixed (default: one per area, plus a 300-400 m "
      "featureless wall on one long straight), urban, suburban, country, carpark, avenue or wall",
      false, "", "NAME", c);
  TCLAP::ValueArg<std::string> route_from_gt(
      "", "route-from-gt",
      "Oxford gt/radar_odometry.csv whose chained poses and scan times are the route (implies "
      "--world oxford-route; the file is read, never copied)",
      false, "", "CSV", c);
  cmd.parse(argc, argv);

  sim::SimulationConfig config;
  if (!config_file.getValue().empty()) sim::loadSimulationConfig(config_file.getValue(), config);
  if (seed.isSet()) {
    if (seed.getValue() < 0) throw InputError("--seed", "must be >= 0");
    config.seed = static_cast<std::uint64_t>(seed.getValue());
  }
  if (scans.isSet() && length.isSet())
    throw InputError("radarslam simulate", "give --scans or --length-m, not both");
  if (scans.isSet()) {
    if (scans.getValue() < 1 || scans.getValue() > 100000)
      throw InputError("--scans", "must be in 1..100000");
    config.scans = scans.getValue(), config.length_m = 0;
  }
  if (length.isSet()) {
    if (!(length.getValue() > 10 && length.getValue() <= 1e5))
      throw InputError("--length-m", "must be in (10, 100000]");
    config.length_m = length.getValue(), config.scans = 0;
  }
  if (traversal.isSet()) config.traversal = traversal.getValue();
  if (config.traversal < 1 || config.traversal > 2) throw InputError("--traversal", "must be 1 or 2");
  if (world.isSet()) config.world_type = world.getValue();
  if (route_from_gt.isSet()) {
    config.route_from_gt = route_from_gt.getValue();
    if (!world.isSet()) config.world_type = "oxford-route";
  }
  const sim::WorldType world_type = sim::parseWorldType(config.world_type, "--world");
  if (scene.isSet()) config.scene = scene.getValue();
  sim::parseScene(config.scene, "--scene");
  if (world_type != sim::WorldType::OxfordRoute && route_from_gt.isSet())
    throw InputError("--route-from-gt", "only with --world oxford-route");
  if (world_type == sim::WorldType::OxfordRoute) {
    if (config.route_from_gt.empty())
      throw InputError("--route-from-gt", "required with --world oxford-route");
    if (config.length_m > 0) throw InputError("--length-m", "not with --world oxford-route (use --scans)");
    std::error_code ec;
    if (!fs::is_regular_file(followSymlinks(config.route_from_gt), ec))
      throw InputError("--route-from-gt", config.route_from_gt + ": not a readable file");
  }
  if (!weather.getValue().empty()) config.weather = weather.getValue();
  sim::weatherPreset(config.weather);  // validates the name
  if (azimuths.isSet()) config.geometry.azimuths = azimuths.getValue();
  if (bins.isSet()) config.geometry.bins = bins.getValue();
  if (resolution.isSet()) config.geometry.range_resolution_m = resolution.getValue();
  if (rpm.isSet()) config.geometry.rotation_hz = rpm.getValue() / 60.0;
  const auto& g = config.geometry;
  if (g.azimuths < 8 || g.azimuths > 16384) throw InputError("--azimuths", "must be in 8..16384");
  if (g.bins < 16 || g.bins > 65535) throw InputError("--bins", "must be in 16..65535");
  if (!(g.range_resolution_m >= 0.001 && g.range_resolution_m <= 10))
    throw InputError("--resolution", "must be in [0.001, 10] m/bin");
  if (static_cast<long long>(g.azimuths) * g.bins > (1LL << 24))
    throw InputError("--azimuths", "azimuths x bins must be <= 16777216 (one scan image)");
  if (!(g.rotation_hz > 0.1 && g.rotation_hz <= 40)) throw InputError("--rpm", "must be in 6..2400");

  if (!compare.getValue().empty()) {
    checkNoOverlap(compare.getValue(), out.getValue());
    checkFileOutput(out.getValue(), "OUT_DIR");
    return compareReal(compare.getValue(), out.getValue(), config);
  }

  // The sequence is written into a hidden sibling and renamed into place when complete: a failed
  // or interrupted run leaves nothing behind (and the previous simulation, if any, untouched).
  checkSimulationOutput(out.getValue(), force.getValue());
  const fs::path dir = followSymlinks(out.getValue());
  const fs::path staging = stagingSibling(dir, "sim-tmp");
  const TemporaryPath removed_on_signal(staging);
  std::error_code ec;
  fs::remove_all(staging, ec);
  std::optional<cli::ProgressLine> bar;
  sim::SimulationSummary s;
  try {
    s = sim::simulateToDirectory(config, staging, [&](std::size_t d, std::size_t t) {
      if (!bar) bar.emplace("simulate", t);
      d == t ? bar->finish(d) : bar->update(d);
    });
    publishSimulation(staging, dir);
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  std::printf(
      "simulated %zu scans, %.2f km (%s weather, traversal %d, seed %llu); route has %zu loop closures (%zu "
      "in the "
      "opposite direction); %.1f s (%.1f scans/s) -> %s\n",
      s.scans, s.length_m / 1000, config.weather.c_str(), config.traversal,
      static_cast<unsigned long long>(config.seed), s.loops, s.opposite_loops, s.wall_seconds,
      s.wall_seconds > 0 ? static_cast<double>(s.scans) / s.wall_seconds : 0.0, out.getValue().c_str());
  if (world_type != sim::WorldType::Grid)
    std::printf("world: %s, scene %s\n", config.world_type.c_str(), config.scene.c_str());
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("simulate", "Simulate a realistic radar sequence (Oxford format) of a procedural world",
                  runSimulate);
