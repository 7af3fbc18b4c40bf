// radarslam-map-client: an example subscriber of radarslam-map-server. Waits for the latched map
// layers and MapInfo, writes each layer to its files (atomically) as soon as it arrives and frees
// it, and exits once the files of every layer belong to the MapInfo received (same header stamp;
// SHA-256 of the grid equals MapInfo.grid_sha256):
//   OUT/grid.pgm, grid.png, grid.yaml (ROS map_server), OUT/cloud.pcd, OUT/map.bt, OUT/map_info.yaml
// Exit status: 0 received and written, 1 bad input, 2 timed out.
#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <sstream>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/dds/domain.h>
#include <radarslam/dds/map_messages.h>

#include "cli_common.h"

namespace {

using namespace radarslam;
using Clock = std::chrono::steady_clock;

struct Timeout : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class Msg>
bool takeLatest(dds::Subscription<Msg>* sub, std::optional<Msg>& latest) {
  bool got = false;
  if (!sub) return false;
  while (auto m = sub->take(std::chrono::milliseconds(0))) {
    latest = std::move(m);
    got = true;
  }
  return got;
}

// What was written for a layer: the publication (header stamp) it came from and a description.
struct Written {
  std::optional<dds::TimeMsg> stamp;
  std::string what, grid_sha;
};

// Takes every sample that arrived, writes each to its files at once and frees it: the client
// never holds more than one layer.
template <class Msg, class WriteFn>
void takeAndWrite(dds::Subscription<Msg>* sub, const char* name, Written& written, WriteFn&& write) {
  if (!sub) return;
  while (auto m = sub->take(std::chrono::milliseconds(0))) {
    // UNIX time of arrival, to measure from another process's start (docs/dds.md, measurements).
    const double unix_s =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    written.what = write(*m);
    written.stamp = m->header.stamp;
    logger().logFmt(mrpt::system::LVL_INFO, "%s received at UNIX time %.3f: %s, written", name, unix_s,
                    written.what.c_str());
  }
}

int run(int argc, char** argv) {
  cli::CommandLine cmd("map-client",
                       "Receives the maps published by radarslam-map-server over DDS, checks them against "
                       "MapInfo and writes them to files atomically (grid.pgm/png/yaml, cloud.pcd, map.bt, "
                       "map_info.yaml). Exit status 2 on timeout.");
  auto& tc = cmd.tclap();
  TCLAP::ValueArg<std::string> out("o", "out", "Output directory", true, "", "DIR", tc);
  TCLAP::ValueArg<std::string> config(
      "", "config", "Cyclone DDS XML configuration (default: built-in loopback)", false, "", "FILE", tc);
  TCLAP::ValueArg<unsigned> domain("", "domain", "DDS domain id (ROS_DOMAIN_ID), 0..232", false, 0, "N", tc);
  TCLAP::ValueArg<std::string> layers("", "layers", "Layers to wait for, comma-separated (MapInfo always)",
                                      false, "grid,cloud,octomap", "LIST", tc);
  TCLAP::ValueArg<double> timeout("", "timeout", "Give up after this many seconds", false, 30.0, "S", tc);
  TCLAP::ValueArg<std::string> expect("", "expect-grid-sha256",
                                      "Wait for the map whose grid has this SHA-256 (e.g. after a reload)",
                                      false, "", "HEX", tc);
  cmd.parse(argc, argv);

  bool want_grid = false, want_cloud = false, want_octomap = false;
  {
    std::stringstream ss(layers.getValue());
    std::string item;
    while (std::getline(ss, item, ',')) {
      if (item == "grid")
        want_grid = true;
      else if (item == "cloud")
        want_cloud = true;
      else if (item == "octomap")
        want_octomap = true;
      else
        throw InputError("--layers", "unknown layer '" + item + "' (use grid, cloud, octomap)");
    }
  }
  if (!(timeout.getValue() > 0)) throw InputError("--timeout", "must be > 0");
  const std::string xml = config.isSet() ? dds::readConfigFile(config.getValue()) : dds::kLoopbackConfigXml;
  const std::filesystem::path out_dir = out.getValue();

  const auto t0 = Clock::now();
  const auto deadline =
      t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout.getValue()));
  dds::Domain dom(domain.getValue(), xml);
  const auto latched = dds::TopicQos::latched();
  dds::Subscription<dds::MapInfoMsg> info_sub(dom, dds::kMapInfoTopic, latched);
  std::unique_ptr<dds::Subscription<dds::OccupancyGridMsg>> grid_sub;
  std::unique_ptr<dds::Subscription<dds::PointCloud2Msg>> cloud_sub;
  std::unique_ptr<dds::Subscription<dds::OctomapMsg>> octo_sub;
  dds::WaitSet ws(dom);
  ws.attach(info_sub);
  if (want_grid)
    ws.attach(*(
        grid_sub = std::make_unique<dds::Subscription<dds::OccupancyGridMsg>>(dom, dds::kMapTopic, latched)));
  if (want_cloud)
    ws.attach(*(cloud_sub = std::make_unique<dds::Subscription<dds::PointCloud2Msg>>(dom, dds::kCloudMapTopic,
                                                                                     latched)));
  if (want_octomap)
    ws.attach(
        *(octo_sub = std::make_unique<dds::Subscription<dds::OctomapMsg>>(dom, dds::kOctomapTopic, latched)));

  logger().logFmt(mrpt::system::LVL_INFO, "waiting for the map on DDS domain %u (layers %s, timeout %.1f s)",
                  domain.getValue(), layers.getValue().c_str(), timeout.getValue());
  std::filesystem::create_directories(out_dir);
  std::optional<dds::MapInfoMsg> info;
  Written grid, cloud, octo;
  std::string waiting;
  for (;;) {
    takeLatest(&info_sub, info);
    // Each layer is written as it arrives (atomically, file by file) and freed; one that belongs
    // to another publication than MapInfo is overwritten when the matching one arrives.
    takeAndWrite(grid_sub.get(), "grid", grid, [&](const dds::OccupancyGridMsg& m) {
      grid.grid_sha = dds::gridSha256(m);
      dds::writeGridFiles(m, out_dir, "grid");
      return std::to_string(m.width) + "x" + std::to_string(m.height);
    });
    takeAndWrite(cloud_sub.get(), "cloud", cloud, [&](const dds::PointCloud2Msg& m) {
      dds::writePcdFile(m, out_dir / "cloud.pcd");
      return std::to_string(m.width) + " points";
    });
    takeAndWrite(octo_sub.get(), "octomap", octo, [&](const dds::OctomapMsg& m) {
      dds::writeOctomapFile(m, out_dir / "map.bt");
      return std::to_string(m.data.size()) + " bytes";
    });
    // Complete = every wanted layer from the same publication as MapInfo (same header stamp).
    waiting.clear();
    if (!info)
      waiting += " map_info";
    else if (!expect.getValue().empty() && info->grid_sha256 != expect.getValue())
      waiting += " map_info(expected grid)";
    auto current = [&](const Written& w) { return info && w.stamp && *w.stamp == info->header.stamp; };
    if (want_grid && (!current(grid) || grid.grid_sha != info->grid_sha256)) waiting += " grid";
    if (want_cloud && !current(cloud)) waiting += " cloud";
    if (want_octomap && !current(octo)) waiting += " octomap";
    if (waiting.empty()) break;
    const auto now = Clock::now();
    if (now >= deadline)
      throw Timeout("timed out after " + std::to_string(timeout.getValue()) + " s waiting for:" + waiting);
    ws.wait(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now) +
            std::chrono::milliseconds(1));
  }
  const double received_s = std::chrono::duration<double>(Clock::now() - t0).count();

  char yaml[1024];
  std::snprintf(yaml, sizeof yaml,
                "map_name: \"%s\"\nrevision: %u\nformat_version: %u\nkeyframes: %u\ncreated_ns: %lld\n"
                "grid_sha256: \"%s\"\nmanifest_sha256: \"%s\"\n",
                info->map_name.c_str(), info->revision, info->format_version, info->keyframes,
                static_cast<long long>(dds::fromTimeMsg(info->created)), info->grid_sha256.c_str(),
                info->manifest_sha256.c_str());
  writeTextAtomically(out_dir / "map_info.yaml", yaml);
  auto what = [](const Written& w) { return w.stamp ? w.what : std::string("-"); };
  std::printf("received map '%s' revision %u in %.3f s: grid %s, cloud %s, octomap %s; grid sha256 %s\n",
              info->map_name.c_str(), info->revision, received_s, what(grid).c_str(), what(cloud).c_str(),
              what(octo).c_str(), info->grid_sha256.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const Timeout& e) {
    std::cerr << "radarslam-map-client: error: " << e.what() << "\n";
    return 2;
  } catch (const radarslam::InputError& e) {
    std::cerr << "radarslam-map-client: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "radarslam-map-client: error: " << radarslam::describeException(e) << "\n";
    return 1;
  }
}
