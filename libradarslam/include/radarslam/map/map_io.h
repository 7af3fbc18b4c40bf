#pragma once
// The versioned on-disk map (a directory maps/NAME/, format in maps/README.md): manifest.yaml
// (version, geometry, counts, SHA-256 per file), parameters.yaml, keyframes.bin, points.bin,
// graph.bin, and (format 2, optional) the published layers in layers/ (map/map_layers.h). Saving is atomic
// for the whole directory: a crash at any point leaves the old or the new complete map loadable.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "radarslam/map/keyframe_map.h"
#include "radarslam/map/map_layers.h"

namespace radarslam {

/// The newest map format this build reads and the one it writes. 1: keyframes, points, graph;
/// 2: also the precomputed layers (grid, cloud, OctoMap) under `layers:` (optional). Every older
/// version still loads.
constexpr std::uint32_t kMapFormatVersion = 2;

/// A plain name ("campus") resolves to maps/NAME relative to the current directory, or to
/// $RADARSLAM_MAPS_DIR/NAME if that exists and ./maps/NAME does not; anything with a '/' (or '.',
/// '..') is a path and is used as is.
std::filesystem::path resolveMapPath(const std::string& name_or_path);

struct MapSaveHooks {
  /// Called after each file of the temporary directory is written (file name); tests throw from it
  /// to simulate a crash in the middle of a save.
  std::function<void(const std::string& file)> after_file;
  /// Called with the temporary directory once the map files are in it, before the swap: products
  /// written there (trajectories, previews, reports) replace the old ones in the same swap, and if
  /// it throws the previous map (with its products) stays as it was.
  std::function<void(const std::filesystem::path& tmp_dir)> write_products;
};

/// Writes `map` to directory `dir` atomically: everything goes into the sibling `.NAME.map-tmp`
/// (fsynced), then the old map (if any) is renamed to `.NAME.map-backup`, the new one renamed into
/// place and the backup deleted. Anything else inside an old `dir` (e.g. exports/) goes with it.
/// Throws InputError naming the file on I/O failure (the previous map stays loadable). Only a map
/// (manifest.yaml), an empty directory or a regular file is replaced: any other non-empty
/// directory is refused. A symbolic link `dir` is written through: the map it points to is replaced.
/// With `layers`, the grid, cloud and OctoMap layers are built with these parameters and written
/// into layers/ of the same temporary directory, listed in the manifest (map/map_layers.h).
void saveMap(const KeyframeMap& map, const std::filesystem::path& dir, const MapSaveHooks& hooks = {},
             const std::optional<MapLayerParams>& layers = std::nullopt);

/// What a map server needs without loading the map: the manifest's version, creation time,
/// keyframe count and layers section (nullopt: none, build them from the keyframes).
struct MapManifestSummary {
  std::uint32_t format_version = 0;
  StampNs created_ns = 0;
  std::uint64_t keyframes = 0;
  std::optional<MapLayersManifest> layers;
};
/// Reads `dir`/manifest.yaml only. Throws InputError naming it if it is missing or malformed.
MapManifestSummary readMapManifest(const std::filesystem::path& dir);

/// One file a manifest lists: path relative to the map directory, size, SHA-256 (hex).
struct MapFileEntry {
  std::string name;
  std::uint64_t bytes = 0;
  std::string sha256;
};
/// The files `dir`/manifest.yaml lists: the map's own (`files:`, what loadMap reads) and, with
/// `with_layers`, the layer files (`layers.files`, format 2; none if the map has no layers).
/// Reads the manifest only. Throws InputError naming it if it is missing or an entry is malformed.
std::vector<MapFileEntry> listMapFiles(const std::filesystem::path& dir, bool with_layers);

/// Reads and verifies a map directory. If `dir` is missing but its `.NAME.map-backup` is complete
/// (a save was interrupted between the two renames) the backup is moved back and loaded.
/// Throws InputError naming the file and the problem: missing, checksum mismatch, truncated,
/// newer format version, malformed.
KeyframeMap loadMap(const std::filesystem::path& dir);

/// The sibling directories used by saveMap (exposed for tests and tools).
std::filesystem::path mapTempDir(const std::filesystem::path& dir);
std::filesystem::path mapBackupDir(const std::filesystem::path& dir);

}  // namespace radarslam
