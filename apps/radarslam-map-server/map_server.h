#pragma once
// The map server's state: the map directory it serves, the latched DDS publishers, and the
// manifest fingerprint that tells when saveMap has swapped in a new map.
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <radarslam/dds/domain.h>
#include <radarslam/dds/map_file_publisher.h>
#include <radarslam/dds/messages.h>
#include <radarslam/map/map_exports.h>
#include <radarslam/map/map_io.h>

namespace radarslam::map_server {

struct Layers {
  bool grid = true, cloud = true, octomap = true;
  bool files = true;  ///< the map's own files (rt/radarslam/map_files), for `localize dds:`
};
/// "grid,cloud,octomap,files" (any subset, any order). Throws InputError("--layers", ...).
Layers parseLayers(const std::string& text);

struct ServerParams {
  std::filesystem::path map_dir;
  Layers layers;
  /// Used only to build the layers of a map that has none saved (format 1, or saved without
  /// layers), or when `resolution_set` asks for another resolution than the saved layers'.
  GridExportParams grid;
  OctomapExportParams octomap;
  bool resolution_set = false;    ///< --resolution given: grid.resolution_m = octomap.resolution_m
  dds::MapFilesParams map_files;  ///< the map files layer (layers.files)
};

class MapServer {
 public:
  MapServer(dds::Domain& domain, ServerParams params);

  /// Publishes the map's layers and MapInfo: the grid and MapInfo first, then each other layer as
  /// soon as it is read, the map's own files last (checked against the manifest before any is
  /// sent; a bad one throws and the previous revision's files stay published). A map with saved layers
  /// (map/map_layers.h) is served from the layer files alone (checked against the manifest; the keyframes are
  /// not loaded); an older map's layers are built from its keyframes (with a warning). Throws InputError
  /// naming the file if the map or a layer file is bad: nothing is published if the manifest or the grid is
  /// bad; layers published before a later one failed stay published.
  void load();
  /// Reloads if the manifest changed since the last load (checked by content hash). Returns true
  /// if a new map was published. A map that fails to load is reported once (WARN) and the last
  /// good map stays published; it is retried only when mapFingerprint() changes.
  bool reloadIfChanged();
  std::uint32_t revision() const { return revision_; }

 private:
  dds::Domain& domain_;
  ServerParams params_;
  std::string map_name_;
  void publishSaved(const MapManifestSummary& manifest, dds::MapInfoMsg& info, std::string& summary);
  void publishBuilt(const KeyframeMap& map, dds::MapInfoMsg& info, std::string& summary);
  std::string sinceStart() const;  // " (1.23 s)": time since load() started, for the summary line
  std::chrono::steady_clock::time_point load_start_;
  std::unique_ptr<dds::Publisher<dds::OccupancyGridMsg>> grid_pub_;
  std::unique_ptr<dds::Publisher<dds::PointCloud2Msg>> cloud_pub_;
  std::unique_ptr<dds::Publisher<dds::OctomapMsg>> octomap_pub_;
  std::unique_ptr<dds::Publisher<dds::MapInfoMsg>> info_pub_;
  /// One writer per publication, deep enough for all of its tiles (as the map files layer).
  std::unique_ptr<dds::Publisher<dds::MapTileMsg>> tiles_pub_;
  std::unique_ptr<dds::Publisher<dds::PointCloud2Msg>> cloud_tiles_pub_;
  /// New writers for this publication's grid and cloud tiles (none if 0).
  void replaceTileWriters(std::size_t grid_tiles, std::size_t cloud_tiles);
  std::unique_ptr<dds::MapFilesPublisher> files_pub_;
  std::string loaded_manifest_sha_;
  std::string failed_fingerprint_;  // mapFingerprint() of the map that last failed to load
  std::uint32_t revision_ = 0;
};

/// SHA-256 (hex) of a map's manifest.yaml, or nullopt if it cannot be read (e.g. mid-swap) or is
/// not a regular file (a FIFO is never opened).
std::optional<std::string> manifestSha256(const std::filesystem::path& map_dir);

/// The manifest's SHA-256 plus type, size, mtime and inode of every map file (stat only): changes
/// whenever anything a load reads changes.
std::string mapFingerprint(const std::filesystem::path& map_dir);

}  // namespace radarslam::map_server
