// radarslam simulate: renders a realistic radar sequence of a procedural world in the Oxford
// Radar RobotCar format (see docs/simulator.md), or compares simulated scans with real ones.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/io/dataset.h>
#include <radarslam/radar/cartesian.h>
#include <radarslam/sim/scan_statistics.h>
#include <radarslam/sim/simulator.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli_common.h"
#include "command.h"

namespace fs = std::filesystem;
using namespace radarslam;

namespace {

std::string duration(double s) {
  char buf[32];
  const int t = static_cast<int>(s + 0.5);
  std::snprintf(buf, sizeof buf, "%d:%02d", t / 60, t % 60);
  return buf;
}

class ProgressBar {
 public:
  void operator()(std::size_t done, std::size_t total) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    if (done != total && el - last_ < 0.2) return;
    last_ = el;
    const double rate = el > 0 ? static_cast<double>(done) / el : 0;
    const int width = 30, fill = total ? static_cast<int>(width * done / total) : width;
    std::fprintf(stderr, "\rsimulate [%s%s] %zu/%zu scans  %.1f scans/s  ETA %s ",
                 std::string(fill, '#').c_str(), std::string(width - fill, '.').c_str(), done, total, rate,
                 duration(rate > 0 ? static_cast<double>(total - done) / rate : 0).c_str());
    if (done == total) std::fprintf(stderr, "\n");
  }

 private:
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  double last_ = -1;
};

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
  CObservationRadarScan::Ptr first_real;
  for (std::size_t i = 0; i < reader->size(); ++i) {
    const auto scan = reader->readScan(i);
    if (!first_real) first_real = scan;
    real_stats.push_back(sim::computeScanStatistics(*scan));
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
  }
  const auto real = sim::averageStatistics(real_stats), simulated = sim::averageStatistics(sim_stats);
  std::cout << "real: " << real_dir.string() << " (" << count << " scans)   simulated: seed " << config.seed
            << ", " << count << " scans\n"
            << sim::compareStatisticsTable(real, simulated);
  PolarToCartesian cart(CartesianParams{.size_px = 400, .m_per_px = 0.4});
  cv::Mat side;
  cv::hconcat(labelled(cart.convert(*first_real), "real (Oxford)"),
              labelled(cart.convert(shown), "simulated"), side);
  std::vector<unsigned char> bytes;
  cv::imencode(".png", side, bytes, {cv::IMWRITE_PNG_COMPRESSION, 9});
  writeBytesAtomically(out_png, bytes);
  std::cout << "wrote " << out_png.string() << " (" << bytes.size() / 1024 << " KB)\n";
  return 0;
}

bool nonEmptyDir(const fs::path& p) { return fs::exists(p) && (!fs::is_directory(p) || !fs::is_empty(p)); }

int runSimulate(int argc, char** argv) {
  cli::CommandLine cmd(
      "simulate",
      "Simulate a Navtech-like 360-degree radar driving through a procedural city and countryside; "
      "writes an Oxford Radar RobotCar-format sequence (radar/*.png, radar.timestamps, "
      "gt/radar_odometry.csv, gt/poses.tum). Default: the >= 3 km demo route in clear weather.");
  auto& c = cmd.tclap();
  TCLAP::UnlabeledValueArg<std::string> out(
      "OUT_DIR", "Output directory (with --compare-real: the output PNG)", true, "", "OUT_DIR", c);
  TCLAP::ValueArg<std::string> compare(
      "", "compare-real",
      "Compare simulated scans with the real Oxford scans in DIR: print intensity "
      "statistics and write a side-by-side Cartesian PNG to OUT_DIR",
      false, "", "DIR", c);
  TCLAP::SwitchArg force("", "force", "Write into a non-empty OUT_DIR (replacing a previous simulation)", c);
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

  if (!compare.getValue().empty()) return compareReal(compare.getValue(), out.getValue(), config);

  const fs::path dir = out.getValue();
  if (nonEmptyDir(dir)) {
    if (!force.getValue())
      throw InputError(dir.string(),
                       "output directory is not empty (use --force to replace a previous simulation)");
    std::error_code ec;  // remove only what a simulation writes
    fs::remove_all(dir / "radar", ec);
    fs::remove(dir / "radar.timestamps", ec);
    fs::remove(dir / "gt" / "radar_odometry.csv", ec);
    fs::remove(dir / "gt" / "poses.tum", ec);
  }
  ProgressBar bar;
  const auto s = sim::simulateToDirectory(config, dir, [&](std::size_t d, std::size_t t) { bar(d, t); });
  std::printf(
      "simulated %zu scans, %.2f km (%s weather, traversal %d, seed %llu); route has %zu loop closures (%zu "
      "in the "
      "opposite direction); %.1f s (%.1f scans/s) -> %s\n",
      s.scans, s.length_m / 1000, config.weather.c_str(), config.traversal,
      static_cast<unsigned long long>(config.seed), s.loops, s.opposite_loops, s.wall_seconds,
      s.wall_seconds > 0 ? static_cast<double>(s.scans) / s.wall_seconds : 0.0, dir.string().c_str());
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("simulate", "Simulate a realistic radar sequence (Oxford format) of a procedural world",
                  runSimulate);
