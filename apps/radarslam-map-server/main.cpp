// radarslam-map-server: publishes a saved map (maps/NAME) over DDS with ROS 2 naming and latched
// QoS: the occupancy grid on rt/map (ROS 2 /map), the point cloud on rt/radarslam/cloud_map, the
// OctoMap on rt/radarslam/octomap, radarslam/MapInfo on rt/radarslam/map_info and the map's own files
// (radarslam/MapFileChunk, for `radarslam localize dds:`) on rt/radarslam/map_files. Reloads when
// the map on disk changes (manifest polled every --poll seconds) or on SIGHUP; exits cleanly on
// SIGINT/SIGTERM. Idle: the main thread sleeps in sigtimedwait, nothing polls faster than --poll.
#include <csignal>
#include <cstring>
#include <ctime>
#include <exception>
#include <iostream>

#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/dds/domain.h>
#include <radarslam/map/map_io.h>
#include <radarslam/obs/registration.h>

#include "cli_common.h"
#include "map_server.h"

namespace {

using namespace radarslam;
using mrpt::system::LVL_INFO;

int run(int argc, char** argv) {
  cli::CommandLine cmd(
      "map-server",
      "Publishes a saved radarslam map over DDS (ROS 2 wire-compatible, latched): "
      "rt/map (nav_msgs/OccupancyGrid), rt/radarslam/cloud_map (sensor_msgs/PointCloud2), "
      "rt/radarslam/octomap (octomap_msgs/Octomap), rt/radarslam/map_info (radarslam/MapInfo), "
      "rt/radarslam/map_files (radarslam/MapFileChunk: the map's own files, for `radarslam localize dds:`). "
      "Reloads when the map changes on disk or on SIGHUP; SIGINT/SIGTERM stop it.");
  auto& tc = cmd.tclap();
  TCLAP::ValueArg<std::string> map("", "map", "Map name (maps/NAME) or directory", true, "", "NAME|DIR", tc);
  TCLAP::ValueArg<std::string> config("", "config",
                                      "Cyclone DDS XML configuration (default: built-in loopback only, "
                                      "as config/dds.xml)",
                                      false, "", "FILE", tc);
  TCLAP::ValueArg<unsigned> domain("", "domain", "DDS domain id (ROS_DOMAIN_ID), 0..232", false, 0, "N", tc);
  TCLAP::ValueArg<std::string> layers("", "layers",
                                      "Layers to publish, comma-separated (files: manifest.yaml and the map "
                                      "files it lists, what `radarslam localize dds:` loads)",
                                      false, "grid,cloud,octomap,files", "LIST", tc);
  TCLAP::SwitchArg files_with_layers("", "files-with-layers",
                                     "The files layer also carries layers/* (grid, cloud, OctoMap files; "
                                     "not needed to localise, already on their own topics)",
                                     tc);
  TCLAP::ValueArg<std::size_t> files_chunk("", "files-chunk-bytes",
                                           "Bytes of map file data per rt/radarslam/map_files sample", false,
                                           std::size_t{4} << 20, "N", tc);
  TCLAP::ValueArg<double> resolution(
      "", "resolution",
      "Grid and OctoMap cell size [m] (default: the saved layers', 0.2 for a "
      "map without saved layers; another value builds them from the keyframes)",
      false, 0.2, "M", tc);
  TCLAP::ValueArg<double> poll("", "poll", "Seconds between checks of the map's manifest", false, 1.0, "S",
                               tc);
  cmd.parse(argc, argv);

  if (!(resolution.getValue() > 0)) throw InputError("--resolution", "must be > 0");
  if (!(poll.getValue() >= 0.01)) throw InputError("--poll", "must be >= 0.01 s");
  if (files_chunk.getValue() < 1 || files_chunk.getValue() > dds::kMaxMapFileChunkBytes)
    throw InputError("--files-chunk-bytes", "must be 1.." + std::to_string(dds::kMaxMapFileChunkBytes));
  map_server::ServerParams params;
  params.map_dir = resolveMapPath(map.getValue());
  params.layers = map_server::parseLayers(layers.getValue());
  params.grid.resolution_m = resolution.getValue();
  params.octomap.resolution_m = resolution.getValue();
  params.resolution_set = resolution.isSet();
  params.map_files.with_layers = files_with_layers.getValue();
  params.map_files.chunk_bytes = files_chunk.getValue();
  if (!std::filesystem::is_directory(params.map_dir))
    throw InputError(params.map_dir.string(), "no such map directory");
  const std::string xml = config.isSet() ? dds::readConfigFile(config.getValue()) : dds::kLoopbackConfigXml;

  // Block the signals in every thread (DDS threads inherit the mask) and take them synchronously.
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, s);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  dds::Domain dds_domain(domain.getValue(), xml);
  map_server::MapServer server(dds_domain, params);
  server.load();
  logger().logFmt(LVL_INFO, "serving '%s' on DDS domain %u (SIGHUP reloads, SIGINT/SIGTERM stop)",
                  params.map_dir.string().c_str(), domain.getValue());

  const double p = poll.getValue();
  timespec period{static_cast<time_t>(p),
                  static_cast<long>((p - static_cast<double>(static_cast<time_t>(p))) * 1e9)};
  for (;;) {
    siginfo_t info;
    const int sig = sigtimedwait(&signals, &info, &period);
    if (sig == SIGINT || sig == SIGTERM) {
      logger().logFmt(LVL_INFO, "%s: shutting down (served %u revisions)", strsignal(sig), server.revision());
      return 0;
    }
    if (sig == SIGHUP) {
      logger().logFmt(LVL_INFO, "SIGHUP: reloading");
      try {
        server.load();
      } catch (const std::exception& e) {
        logger().logFmt(mrpt::system::LVL_WARN, "reload failed, keeping revision %u: %s", server.revision(),
                        e.what());
      }
      continue;
    }
    server.reloadIfChanged();  // timeout (or EINTR): poll the manifest
  }
}

}  // namespace

int main(int argc, char** argv) {
  radarslam::registerRadarslamClasses();
  try {
    return run(argc, argv);
  } catch (const radarslam::InputError& e) {
    std::cerr << "radarslam-map-server: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "radarslam-map-server: error: " << radarslam::describeException(e) << "\n";
    return 1;
  }
}
