// radarslam-map-client: an example subscriber of radarslam-map-server. Waits for the latched map
// layers and MapInfo, writes each layer to its files (atomically) as soon as it arrives and frees
// it, and exits once the files of every layer belong to the MapInfo received (same header stamp;
// SHA-256 of the grid equals MapInfo.grid_sha256):
//   OUT/grid.pgm, grid.png, grid.yaml (ROS map_server), OUT/cloud.pcd, OUT/map.bt, OUT/map_info.yaml
// A tiled grid (docs/dds.md, "Tiled grids"): rt/map is the overview (OUT/overview.pgm/png/yaml) and
// OUT/grid.pgm + grid.yaml are reassembled from the tiles as they arrive (no PNG of the full grid),
// and OUT/cloud.pcd is appended tile by tile from rt/radarslam/cloud_map_tiles.
// Exit status: 0 received and written, 1 bad input, 2 timed out.
#include <chrono>
#include <cstdio>
#include <deque>
#include <exception>
#include <iostream>
#include <optional>
#include <sstream>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/dds/cloud_tiles.h>
#include <radarslam/dds/domain.h>
#include <radarslam/dds/grid_tiles.h>
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

// Logs the UNIX time of a layer's arrival, to measure from another process's start (docs/dds.md).
double unixNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}
void logArrival(const char* name, const std::string& what, double unix_s) {
  logger().logFmt(mrpt::system::LVL_INFO, "%s received at UNIX time %.3f: %s, written", name, unix_s,
                  what.c_str());
}

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
  std::unique_ptr<dds::Subscription<dds::PointCloud2Msg>> cloud_sub, cloud_tiles_sub;
  std::unique_ptr<dds::Subscription<dds::OctomapMsg>> octo_sub;
  std::unique_ptr<dds::Subscription<dds::MapTileMsg>> tiles_sub;
  dds::WaitSet ws(dom);
  ws.attach(info_sub);
  if (want_grid)
    ws.attach(*(
        grid_sub = std::make_unique<dds::Subscription<dds::OccupancyGridMsg>>(dom, dds::kMapTopic, latched)));
  if (want_grid)  // KEEP_ALL: no tile of a publication may be lost while the client writes another
    ws.attach(*(tiles_sub = std::make_unique<dds::Subscription<dds::MapTileMsg>>(
                    dom, dds::kMapTilesTopic, dds::TopicQos::latchedAll())));
  if (want_cloud)
    ws.attach(*(cloud_tiles_sub = std::make_unique<dds::Subscription<dds::PointCloud2Msg>>(
                    dom, dds::kCloudMapTilesTopic, dds::TopicQos::latchedAll())));
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
  Written grid, overview, cloud, octo;
  std::optional<dds::OccupancyGridMsg> pending_grid;   // rt/map until its MapInfo says what it is
  double pending_grid_unix = 0;                        // ... and when it arrived
  double grid_origin_x = 0, grid_origin_y = 0;         // of the overview: the tiled grid's corner
  std::unique_ptr<dds::TiledGridWriter> tiled;         // the full grid of a tiled publication
  std::optional<dds::TimeMsg> tiled_stamp;             // ... its publication
  std::deque<dds::MapTileMsg> early_tiles;             // tiles taken before their MapInfo
  std::unique_ptr<dds::TiledCloudWriter> tiled_cloud;  // the cloud of a tiled publication
  std::optional<dds::TimeMsg> tiled_cloud_stamp;
  std::deque<dds::PointCloud2Msg> early_cloud_tiles;
  constexpr std::size_t kMaxEarlyTiles = 64;
  constexpr int kTilesPerPass = 8;
  std::string waiting;
  for (;;) {
    takeLatest(&info_sub, info);
    const bool tiled_info = info && info->tile_cells > 0;
    // Each layer is written as it arrives (atomically, file by file) and freed; one that belongs
    // to another publication than MapInfo is overwritten when the matching one arrives. rt/map is
    // held until MapInfo tells whether it is the grid or a tiled grid's overview.
    if (grid_sub)
      while (auto m = grid_sub->take(std::chrono::milliseconds(0))) {
        pending_grid = std::move(m);
        pending_grid_unix = unixNow();
      }
    if (pending_grid && info && pending_grid->header.stamp == info->header.stamp) {
      Written& w = tiled_info ? overview : grid;
      w.grid_sha = dds::gridSha256(*pending_grid);
      dds::writeGridFiles(*pending_grid, out_dir, tiled_info ? "overview" : "grid");
      w.stamp = pending_grid->header.stamp;
      w.what = std::to_string(pending_grid->width) + "x" + std::to_string(pending_grid->height);
      grid_origin_x = pending_grid->origin.x;
      grid_origin_y = pending_grid->origin.y;
      logArrival(tiled_info ? "grid overview" : "grid", w.what, pending_grid_unix);
      pending_grid.reset();
    }
    if (tiles_sub && !tiled_info)  // tiles before their MapInfo (rare: the server sends it first)
      while (auto t = tiles_sub->take(std::chrono::milliseconds(0))) {
        early_tiles.push_back(std::move(*t));
        if (early_tiles.size() > kMaxEarlyTiles) early_tiles.pop_front();
      }
    if (tiles_sub && tiled_info) {
      if (!tiled_stamp || !(*tiled_stamp == info->header.stamp)) {  // a new tiled publication
        tiled.reset();
        tiled = std::make_unique<dds::TiledGridWriter>(out_dir, *info);
        tiled_stamp = info->header.stamp;
      }
      for (; tiled && !early_tiles.empty(); early_tiles.pop_front()) tiled->add(early_tiles.front());
      // A few tiles per pass, so rt/map, MapInfo and the other layers are not starved by them.
      for (int n = 0; tiled && !tiled->complete() && n < kTilesPerPass; ++n) {
        auto t = tiles_sub->take(std::chrono::milliseconds(0));
        if (!t) break;
        tiled->add(*t);  // a tile of another publication is dropped
      }
      const bool have_overview = overview.stamp && *overview.stamp == info->header.stamp;
      if (tiled && tiled->complete() && have_overview) {
        grid.grid_sha = tiled->finish(grid_origin_x, grid_origin_y);
        grid.stamp = info->header.stamp;
        grid.what = std::to_string(info->grid_width) + "x" + std::to_string(info->grid_height) + " from " +
                    std::to_string(tiled->expected()) + " tiles";
        tiled.reset();  // tiled_stamp stays: this publication is done
        logArrival("grid", grid.what, unixNow());
      }
    }
    const bool tiled_cloud_info = info && info->cloud_tile_count > 0;
    if (cloud_tiles_sub && !tiled_cloud_info)  // before their MapInfo (rare: the server sends it first)
      while (auto t = cloud_tiles_sub->take(std::chrono::milliseconds(0))) {
        early_cloud_tiles.push_back(std::move(*t));
        if (early_cloud_tiles.size() > kMaxEarlyTiles) early_cloud_tiles.pop_front();
      }
    if (cloud_tiles_sub && tiled_cloud_info) {
      if (!tiled_cloud_stamp || !(*tiled_cloud_stamp == info->header.stamp)) {  // a new publication
        tiled_cloud.reset();
        tiled_cloud = std::make_unique<dds::TiledCloudWriter>(out_dir, *info);
        tiled_cloud_stamp = info->header.stamp;
      }
      for (; tiled_cloud && !early_cloud_tiles.empty(); early_cloud_tiles.pop_front())
        tiled_cloud->add(early_cloud_tiles.front());
      for (int n = 0; tiled_cloud && !tiled_cloud->complete() && n < kTilesPerPass; ++n) {
        auto t = cloud_tiles_sub->take(std::chrono::milliseconds(0));
        if (!t) break;
        tiled_cloud->add(*t);  // a tile of another publication is dropped
      }
      if (tiled_cloud && tiled_cloud->complete()) {
        tiled_cloud->finish();
        cloud.stamp = info->header.stamp;
        cloud.what = std::to_string(info->cloud_points) + " points from " +
                     std::to_string(info->cloud_tile_count) + " tiles";
        tiled_cloud.reset();
        logArrival("cloud", cloud.what, unixNow());
      }
    }
    // A whole cloud is written as it arrives; while MapInfo says the cloud comes as tiles, one that
    // is not from a later publication is stale and dropped.
    const Written before = cloud;
    bool dropped = false;
    takeAndWrite(cloud_sub.get(), "cloud", cloud, [&](const dds::PointCloud2Msg& m) {
      dropped = tiled_cloud_info && dds::fromTimeMsg(m.header.stamp) <= dds::fromTimeMsg(info->header.stamp);
      if (dropped) return std::string("dropped: older than the tiled publication");
      dds::writePcdFile(m, out_dir / "cloud.pcd");
      return std::to_string(m.width) + " points";
    });
    if (dropped) cloud = before;  // what was written still stands
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
    if (want_grid && tiled_info && (!current(overview) || overview.grid_sha != info->overview_sha256))
      waiting += " grid_overview";
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
