#pragma once
// The published layers of a map, built when the map is saved (saveMap with layer parameters, or
// `radarslam map-layers`) and stored in its directory, so a map server publishes them without
// loading the keyframes (format in maps/README.md):
//   layers/grid.pgm   8-bit P5, top row = highest y, pixel = round(255 * (100 - cell) / 100),
//                     205 = unknown (as the map client writes it); exact inverse to the cells
//   layers/grid.yaml  ROS map_server YAML of grid.pgm (mode scale)
//   layers/grid_overview.pgm, layers/grid_tiles.txt   only for a grid large enough to be tiled
//                     (map/grid_tiles.h): the downsampled overview (same pixel coding) and the
//                     index of the tiles with a known cell ("radarslam grid tiles 1", then
//                     "tx ty sha256" per tile)
//   layers/cloud_tiles.txt   with a tiled grid: cloud.pcd holds the points sorted by tile
//                     (map/cloud_tiles.h), this file their ranges ("radarslam cloud tiles 1",
//                     then "tx ty first count sha256" per tile)
//   layers/cloud.pcd  PCD v0.7 DATA binary, x y z intensity FLOAT32: the data is the
//                     sensor_msgs/PointCloud2 payload byte for byte
//   layers/map.bt     OctoMap .bt: the body is the octomap_msgs/Octomap (binary) data
// manifest.yaml lists them under `layers:` with the parameters they were built with, the grid's
// geometry and each file's size and SHA-256.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "radarslam/core/yaml_params.h"
#include "radarslam/map/grid_tiles.h"
#include "radarslam/map/keyframe_map.h"
#include "radarslam/map/map_exports.h"

namespace radarslam {

/// What the layers are built with: YAML section `map_layers` (docs/parameters.md).
struct MapLayerParams {
  GridExportParams grid;        ///< grid_resolution_m, grid_margin_m, grid_log_odds_{hit,miss,clamp}
  OctomapExportParams octomap;  ///< octomap_fill, octomap_resolution_m, octomap_max_range_m
  GridTilingParams tiling;      ///< grid_tile_cells, grid_tile_above_cells, grid_overview_max_cells
};
/// Reads the keys of the `map_layers` section (all optional).
void loadParams(const YamlParams& yaml, MapLayerParams& params);

/// One layer file as the manifest lists it.
struct LayerFileEntry {
  std::string key;   ///< grid, grid_yaml, cloud, octomap
  std::string name;  ///< path relative to the map directory, e.g. "layers/grid.pgm"
  std::uint64_t bytes = 0;
  std::string sha256;
};

/// The `layers:` section of a manifest: parameters, grid geometry, files.
struct MapLayersManifest {
  MapLayerParams params;
  std::uint32_t grid_width = 0, grid_height = 0;
  double grid_origin_x = 0, grid_origin_y = 0;
  /// SHA-256 of the grid's cells (the OccupancyGrid data, = MapInfo.grid_sha256), so a server need
  /// not hash them again; empty if the manifest has none.
  std::string grid_cells_sha256;
  /// The grid's tiles and overview (tiling.tiled(): files grid_overview and grid_tiles exist).
  /// A manifest written before tiling existed has no grid_tile_cells key: never tiled.
  GridTiling tiling;
  std::string grid_overview_cells_sha256;  ///< SHA-256 of the overview's cells (tiled grids)
  std::uint64_t cloud_points = 0;
  /// SHA-256 of the cloud's data section (tiled maps: the points sorted by tile, as the tiles
  /// reassemble it)
  std::string cloud_data_sha256;
  /// grid, grid_yaml, [grid_overview, grid_tiles,] cloud, [cloud_tiles,] octomap (in this order)
  std::vector<LayerFileEntry> files;
  const LayerFileEntry& file(const std::string& key) const;
};

/// The cells of an occupancy grid message: round(100 * P(occupied)), -1 where never observed.
std::vector<std::int8_t> occupancyCells(const OccupancyRaster& raster);

/// Builds every layer of `map` and writes the files into `map_dir`/layers/ (fsynced; `map_dir`
/// is the temporary directory of a save). Returns the manifest section describing them.
MapLayersManifest writeMapLayers(const KeyframeMap& map, const std::filesystem::path& map_dir,
                                 const MapLayerParams& params);

/// The manifest text of the section (starts with "layers:\n").
std::string layersManifestText(const MapLayersManifest& layers);
/// Parses the `layers` section of a manifest; nullopt if it has none (format version 1, or a map
/// saved without layers). Throws InputError(manifest, key) if it is malformed.
std::optional<MapLayersManifest> parseLayersManifest(const YamlParams& manifest, const std::string& origin);

}  // namespace radarslam
