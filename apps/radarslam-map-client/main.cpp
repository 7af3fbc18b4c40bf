// radarslam-map-client: an example subscriber of radarslam-map-server. Waits for the latched map
// layers and MapInfo, checks that they belong together (same header stamp; SHA-256 of the grid
// equals MapInfo.grid_sha256), writes them atomically as files and exits:
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
  std::optional<dds::MapInfoMsg> info;
  std::optional<dds::OccupancyGridMsg> grid;
  std::optional<dds::PointCloud2Msg> cloud;
  std::optional<dds::OctomapMsg> octo;
  std::string grid_sha;
  std::string waiting;
  for (;;) {
    takeLatest(&info_sub, info);
    if (takeLatest(grid_sub.get(), grid)) grid_sha = dds::gridSha256(*grid);
    takeLatest(cloud_sub.get(), cloud);
    takeLatest(octo_sub.get(), octo);
    // Complete = every wanted layer from the same publication as MapInfo (same header stamp).
    waiting.clear();
    if (!info)
      waiting += " map_info";
    else if (!expect.getValue().empty() && info->grid_sha256 != expect.getValue())
      waiting += " map_info(expected grid)";
    if (want_grid &&
        (!grid || !info || grid_sha != info->grid_sha256 || grid->header.stamp != info->header.stamp))
      waiting += " grid";
    if (want_cloud && (!cloud || !info || cloud->header.stamp != info->header.stamp)) waiting += " cloud";
    if (want_octomap && (!octo || !info || octo->header.stamp != info->header.stamp)) waiting += " octomap";
    if (waiting.empty()) break;
    const auto now = Clock::now();
    if (now >= deadline)
      throw Timeout("timed out after " + std::to_string(timeout.getValue()) + " s waiting for:" + waiting);
    ws.wait(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now) +
            std::chrono::milliseconds(1));
  }
  const double received_s = std::chrono::duration<double>(Clock::now() - t0).count();

  std::filesystem::create_directories(out_dir);
  if (grid) dds::writeGridFiles(*grid, out_dir, "grid");
  if (cloud) dds::writePcdFile(*cloud, out_dir / "cloud.pcd");
  if (octo) dds::writeOctomapFile(*octo, out_dir / "map.bt");
  char yaml[1024];
  std::snprintf(yaml, sizeof yaml,
                "map_name: \"%s\"\nrevision: %u\nformat_version: %u\nkeyframes: %u\ncreated_ns: %lld\n"
                "grid_sha256: \"%s\"\nmanifest_sha256: \"%s\"\n",
                info->map_name.c_str(), info->revision, info->format_version, info->keyframes,
                static_cast<long long>(dds::fromTimeMsg(info->created)), info->grid_sha256.c_str(),
                info->manifest_sha256.c_str());
  writeTextAtomically(out_dir / "map_info.yaml", yaml);
  std::printf("received map '%s' revision %u in %.3f s: grid %s, cloud %s, octomap %s; grid sha256 %s\n",
              info->map_name.c_str(), info->revision, received_s,
              grid ? (std::to_string(grid->width) + "x" + std::to_string(grid->height)).c_str() : "-",
              cloud ? (std::to_string(cloud->width) + " points").c_str() : "-",
              octo ? (std::to_string(octo->data.size()) + " bytes").c_str() : "-", info->grid_sha256.c_str());
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
