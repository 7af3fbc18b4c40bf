#pragma once
// The map server's state: the map directory it serves, the latched DDS publishers, and the
// manifest fingerprint that tells when saveMap has swapped in a new map.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <radarslam/dds/domain.h>
#include <radarslam/map/map_exports.h>

namespace radarslam::map_server {

struct Layers {
  bool grid = true, cloud = true, octomap = true;
};
/// "grid,cloud,octomap" (any subset, any order). Throws InputError("--layers", ...).
Layers parseLayers(const std::string& text);

struct ServerParams {
  std::filesystem::path map_dir;
  Layers layers;
  GridExportParams grid;
  OctomapExportParams octomap;
};

class MapServer {
 public:
  MapServer(dds::Domain& domain, ServerParams params);

  /// Loads the map and publishes every layer and MapInfo. Throws InputError if the map cannot be
  /// loaded (the previously published map, if any, stays published).
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
  std::unique_ptr<dds::Publisher<dds::OccupancyGridMsg>> grid_pub_;
  std::unique_ptr<dds::Publisher<dds::PointCloud2Msg>> cloud_pub_;
  std::unique_ptr<dds::Publisher<dds::OctomapMsg>> octomap_pub_;
  std::unique_ptr<dds::Publisher<dds::MapInfoMsg>> info_pub_;
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
