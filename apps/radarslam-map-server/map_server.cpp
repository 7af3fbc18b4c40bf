#include "map_server.h"

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <sstream>

#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/dds/cloud_tiles.h>
#include <radarslam/dds/grid_tiles.h>
#include <radarslam/dds/map_messages.h>
#include <radarslam/map/layer_files.h>
#include <radarslam/map/map_io.h>
#include <radarslam/map/sha256.h>

namespace radarslam::map_server {

namespace fs = std::filesystem;
using mrpt::system::LVL_INFO;
using mrpt::system::LVL_WARN;

Layers parseLayers(const std::string& text) {
  Layers l{false, false, false, false};
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item == "grid")
      l.grid = true;
    else if (item == "cloud")
      l.cloud = true;
    else if (item == "octomap")
      l.octomap = true;
    else if (item == "files")
      l.files = true;
    else
      throw InputError("--layers", "unknown layer '" + item + "' (use grid, cloud, octomap, files)");
  }
  return l;
}

std::optional<std::string> manifestSha256(const fs::path& map_dir) {
  struct stat st {};  // never open a FIFO (it would block) or a directory
  if (::stat((map_dir / "manifest.yaml").c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  std::ifstream in(map_dir / "manifest.yaml", std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return sha256Hex(ss.str());
}

std::string mapFingerprint(const fs::path& map_dir) {
  std::ostringstream fp;
  fp << manifestSha256(map_dir).value_or("-");
  for (const char* name :
       {"manifest.yaml", "parameters.yaml", "keyframes.bin", "points.bin", "graph.bin", "layers/grid.pgm",
        "layers/grid_overview.pgm", "layers/grid_tiles.txt", "layers/cloud.pcd", "layers/map.bt"}) {
    struct stat st {};
    if (::stat((map_dir / name).c_str(), &st) != 0)
      fp << " -";
    else
      fp << ' ' << st.st_mode << ':' << st.st_size << ':' << st.st_mtim.tv_sec << '.' << st.st_mtim.tv_nsec
         << ':' << st.st_ino;
  }
  return fp.str();
}

MapServer::MapServer(dds::Domain& domain, ServerParams params) : domain_(domain), params_(std::move(params)) {
  map_name_ = params_.map_dir.lexically_normal().filename().string();
  if (map_name_.empty()) map_name_ = params_.map_dir.lexically_normal().parent_path().filename().string();
  const auto latched = dds::TopicQos::latched();
  if (params_.layers.grid)
    grid_pub_ = std::make_unique<dds::Publisher<dds::OccupancyGridMsg>>(domain_, dds::kMapTopic, latched);
  if (params_.layers.cloud)
    cloud_pub_ = std::make_unique<dds::Publisher<dds::PointCloud2Msg>>(domain_, dds::kCloudMapTopic, latched);
  if (params_.layers.octomap)
    octomap_pub_ = std::make_unique<dds::Publisher<dds::OctomapMsg>>(domain_, dds::kOctomapTopic, latched);
  info_pub_ = std::make_unique<dds::Publisher<dds::MapInfoMsg>>(domain_, dds::kMapInfoTopic, latched);
  if (params_.layers.files) files_pub_ = std::make_unique<dds::MapFilesPublisher>(domain_, params_.map_files);
}

void MapServer::load() {
  const auto t0 = load_start_ = std::chrono::steady_clock::now();
  const auto before = manifestSha256(params_.map_dir);
  const MapManifestSummary manifest = readMapManifest(params_.map_dir);  // throws naming the file
  const StampNs now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::system_clock::now().time_since_epoch())
                          .count();
  dds::MapInfoMsg info;
  info.header = {dds::toTimeMsg(now), dds::kMapFrame};
  info.map_name = map_name_;
  info.revision = revision_ + 1;
  info.manifest_sha256 = before.value_or("");

  const auto& saved = manifest.layers;
  const bool other_resolution = saved && params_.resolution_set &&
                                (saved->params.grid.resolution_m != params_.grid.resolution_m ||
                                 saved->params.octomap.resolution_m != params_.octomap.resolution_m);
  std::string summary;
  const char* source = "saved layers";
  if (saved && !other_resolution) {
    info.format_version = manifest.format_version;
    info.keyframes = static_cast<std::uint32_t>(manifest.keyframes);
    info.created = dds::toTimeMsg(manifest.created_ns);
    publishSaved(manifest, info, summary);
  } else {
    if (other_resolution)
      logger().logFmt(
          LVL_INFO, "--resolution %g differs from the saved layers' (%g m): building them from the keyframes",
          params_.grid.resolution_m, saved->params.grid.resolution_m);
    else
      logger().logFmt(LVL_WARN,
                      "map '%s' (format version %u) has no saved layers: building them from the keyframes "
                      "at every load; `radarslam map-layers %s` saves them with the map",
                      map_name_.c_str(), manifest.format_version, params_.map_dir.string().c_str());
    source = "built from the keyframes";
    const KeyframeMap map = loadMap(params_.map_dir);  // throws InputError naming the file
    info.format_version = map.meta.format_version;
    info.keyframes = static_cast<std::uint32_t>(map.keyframes.size());
    info.created = dds::toTimeMsg(map.meta.created_ns);
    publishBuilt(map, info, summary);
  }
  if (files_pub_) {  // last: the layers keep their timing; checked before any chunk is sent
    const dds::MapFilesSummary f =
        files_pub_->publish(params_.map_dir, {map_name_, info.revision, now, before.value_or("")});
    summary += "files " + std::to_string(f.files) + " (" + std::to_string(f.chunks) + " chunks, " +
               std::to_string(f.bytes) + " bytes)" + sinceStart() + ", ";
  }
  // Every file was checked against the manifest read first; a manifest that changed meanwhile
  // means a new map is being swapped in: the next poll publishes it.
  const auto after = manifestSha256(params_.map_dir);
  if (!before || before != after)
    throw InputError(params_.map_dir.string(), "the map changed while it was being read");
  loaded_manifest_sha_ = *after;
  failed_fingerprint_.clear();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  logger().logFmt(LVL_INFO, "published map '%s' revision %u (%u keyframes, %s): %sin %.2f s",
                  map_name_.c_str(), revision_, info.keyframes, source, summary.c_str(), secs);
}

void MapServer::replaceTileWriters(std::size_t grid_tiles, std::size_t cloud_tiles) {
  tiles_pub_.reset();  // the previous publication's tiles go with its writer
  cloud_tiles_pub_.reset();
  if (grid_tiles > 0)
    tiles_pub_ = std::make_unique<dds::Publisher<dds::MapTileMsg>>(
        domain_, dds::kMapTilesTopic, dds::TopicQos::latchedLast(static_cast<std::int32_t>(grid_tiles)));
  if (cloud_tiles > 0) {
    cloud_tiles_pub_ = std::make_unique<dds::Publisher<dds::PointCloud2Msg>>(
        domain_, dds::kCloudMapTilesTopic,
        dds::TopicQos::latchedLast(static_cast<std::int32_t>(cloud_tiles)));
    // A whole cloud latched by an earlier, untiled publication must not outlive it.
    cloud_pub_ = std::make_unique<dds::Publisher<dds::PointCloud2Msg>>(domain_, dds::kCloudMapTopic,
                                                                       dds::TopicQos::latched());
  }
}

// The grid first (what a late joiner needs soonest; for a tiled grid its overview), then MapInfo,
// which names its checksum (and the tiles); then the tiles, then the other layers, each published
// as soon as it is read and freed before the next one. All carry the same header stamp, so a
// client knows which publication each belongs to.
void MapServer::publishSaved(const MapManifestSummary& manifest, dds::MapInfoMsg& info,
                             std::string& summary) {
  const MapLayersManifest& layers = *manifest.layers;
  const StampNs now = dds::fromTimeMsg(info.header.stamp);
  std::vector<GridTileEntry> tiles;
  std::vector<CloudTileEntry> cloud_tiles;
  if (cloud_pub_ && layers.tiling.tiled()) {  // checked before anything is sent
    cloud_tiles = readCloudTileIndexLayer(params_.map_dir, layers);
    dds::describeCloudTiles(info, cloud_tiles, layers.cloud_points, layers.cloud_data_sha256);
  }
  if (grid_pub_ && layers.tiling.tiled()) {
    tiles = readGridTileIndexLayer(params_.map_dir, layers);  // checked before anything is sent
    const dds::OccupancyGridMsg overview = dds::overviewMessage(params_.map_dir, layers, now);
    grid_pub_->publish(overview);
    summary += "grid overview " + std::to_string(overview.width) + "x" + std::to_string(overview.height) +
               sinceStart() + ", ";
    info.grid_sha256 = layers.grid_cells_sha256;
    dds::describeTiles(info, layers.tiling, tiles, layers.grid_overview_cells_sha256);
  } else if (grid_pub_) {
    const dds::OccupancyGridMsg grid = dds::gridMessage(params_.map_dir, layers, now);
    grid_pub_->publish(grid);  // before hashing its cells: a late joiner gets it sooner
    summary += "grid " + std::to_string(grid.width) + "x" + std::to_string(grid.height) + sinceStart() + ", ";
    // The manifest's hash of the cells (from the file just checked against the manifest), if any.
    info.grid_sha256 = layers.grid_cells_sha256.empty() ? dds::gridSha256(grid) : layers.grid_cells_sha256;
    dds::describeTiles(info, layers.tiling, {}, "");
  }
  replaceTileWriters(tiles.size(), cloud_tiles.size());
  info_pub_->publish(info);
  revision_ = info.revision;
  if (!tiles.empty()) {
    const auto res = static_cast<float>(layers.params.grid.resolution_m);
    forEachGridTileLayer(params_.map_dir, layers, tiles,
                         [&](const GridTileEntry& e, const std::vector<std::int8_t>& cells) {
                           tiles_pub_->publish(dds::tileMessage(info, layers.tiling, e, cells, res,
                                                                layers.grid_origin_x, layers.grid_origin_y));
                         });
    summary += std::to_string(tiles.size()) + " tiles of " + std::to_string(layers.tiling.tile_cells) +
               " cells" + sinceStart() + ", ";
  }
  if (!cloud_tiles.empty()) {
    forEachCloudTileLayer(params_.map_dir, layers, cloud_tiles,
                          [&](const CloudTileEntry&, const std::vector<std::uint8_t>& data) {
                            cloud_tiles_pub_->publish(dds::cloudTileMessage(info, data));
                          });
    summary += "cloud " + std::to_string(layers.cloud_points) + " points in " +
               std::to_string(cloud_tiles.size()) + " tiles" + sinceStart() + ", ";
  } else if (cloud_pub_) {
    const dds::PointCloud2Msg cloud = dds::cloudMessage(params_.map_dir, layers, now);
    summary += "cloud " + std::to_string(cloud.width) + " points" + sinceStart() + ", ";
    cloud_pub_->publish(cloud);
  }
  if (octomap_pub_) {
    const dds::OctomapMsg octo = dds::octomapMessage(params_.map_dir, layers, now);
    summary += "octomap " + std::to_string(octo.data.size()) + " bytes" + sinceStart() + ", ";
    octomap_pub_->publish(octo);
  }
}

// An older map: the layers are built from the keyframes (a large grid tiled with the default
// tiling). The OctoMap (grid_columns fill) reuses the grid's occupancy raster when the
// resolutions agree.
void MapServer::publishBuilt(const KeyframeMap& map, dds::MapInfoMsg& info, std::string& summary) {
  const StampNs now = dds::fromTimeMsg(info.header.stamp);
  std::optional<OccupancyRaster> raster;
  const bool share_raster = params_.octomap.fill == OctomapExportParams::Fill::grid_columns &&
                            params_.octomap.resolution_m == params_.grid.resolution_m;
  GridExportParams grid_params = params_.grid;  // tiled when large, as saved layers are
  grid_params.max_cells = std::max(grid_params.max_cells, kMaxLayerGridCells);
  if (grid_pub_ || (octomap_pub_ && share_raster)) raster = buildOccupancy(map, grid_params);
  std::optional<dds::OccupancyGridMsg> grid;
  GridTiling tiling;
  std::vector<GridTileEntry> tiles;
  if (grid_pub_) {
    grid = dds::gridMessage(*raster, now);
    tiling = gridTiling(grid->width, grid->height, GridTilingParams{});
    if (tiling.tiled()) {
      const dds::OccupancyGridMsg overview = dds::overviewMessage(*grid, tiling);
      grid_pub_->publish(overview);
      summary += "grid overview " + std::to_string(overview.width) + "x" + std::to_string(overview.height) +
                 sinceStart() + ", ";
      tiles = gridTileIndex(grid->data, tiling);
      dds::describeTiles(info, tiling, tiles, dds::gridSha256(overview));
    } else {
      grid_pub_->publish(*grid);  // before hashing its cells: a late joiner gets it sooner
      summary +=
          "grid " + std::to_string(grid->width) + "x" + std::to_string(grid->height) + sinceStart() + ", ";
      dds::describeTiles(info, tiling, {}, "");
    }
    info.grid_sha256 = dds::gridSha256(*grid);
  }
  replaceTileWriters(tiles.size(), 0);
  info_pub_->publish(info);
  revision_ = info.revision;
  for (const auto& e : tiles)
    tiles_pub_->publish(dds::tileMessage(info, tiling, e, tileCells(grid->data, tiling, e.tx, e.ty),
                                         grid->resolution, grid->origin.x, grid->origin.y));
  if (!tiles.empty()) summary += std::to_string(tiles.size()) + " tiles" + sinceStart() + ", ";
  grid.reset();
  if (cloud_pub_) {
    const dds::PointCloud2Msg cloud = dds::cloudMessage(map, now);
    summary += "cloud " + std::to_string(cloud.width) + " points" + sinceStart() + ", ";
    cloud_pub_->publish(cloud);
  }
  if (octomap_pub_) {
    const dds::OctomapMsg octo =
        share_raster ? dds::octomapMessage(*raster, now) : dds::octomapMessage(map, params_.octomap, now);
    summary += "octomap " + std::to_string(octo.data.size()) + " bytes" + sinceStart() + ", ";
    octomap_pub_->publish(octo);
  }
}

std::string MapServer::sinceStart() const {
  char buf[32];
  std::snprintf(buf, sizeof buf, " (%.2f s)",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start_).count());
  return buf;
}

bool MapServer::reloadIfChanged() {
  const auto sha = manifestSha256(params_.map_dir);
  if (!sha || *sha == loaded_manifest_sha_) return false;
  // A map that failed to load is retried only once its files change (not on every poll).
  const std::string fingerprint = mapFingerprint(params_.map_dir);
  if (fingerprint == failed_fingerprint_) return false;
  try {
    logger().logFmt(LVL_INFO, "map '%s' changed on disk, reloading", map_name_.c_str());
    load();
    return true;
  } catch (const std::exception& e) {  // InputError (bad map) or a DDS write error
    logger().logFmt(LVL_WARN, "keeping revision %u: %s (retrying when the map's files change)", revision_,
                    e.what());
    failed_fingerprint_ = fingerprint;
    return false;
  }
}

}  // namespace radarslam::map_server
