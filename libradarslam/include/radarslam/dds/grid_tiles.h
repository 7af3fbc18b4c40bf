#pragma once
// Tiled grids over DDS (docs/dds.md, "Tiled grids"): the overview published on rt/map, MapInfo's
// tile index, the radarslam/MapTile messages of rt/radarslam/map_tiles, and a receiver that writes
// the full-resolution grid image from the tiles as they arrive (one tile in memory at a time).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "radarslam/dds/messages.h"
#include "radarslam/map/grid_tiles.h"
#include "radarslam/map/map_layers.h"

namespace radarslam::dds {

/// The overview of a tiled grid as saved with the map (layers/grid_overview.pgm): resolution =
/// overview_factor x the grid's, origin = the grid's corner. Throws InputError naming the file.
OccupancyGridMsg overviewMessage(const std::filesystem::path& map_dir, const MapLayersManifest& layers,
                                 StampNs stamp);
/// The overview of a full grid message (for maps whose layers are built at load).
OccupancyGridMsg overviewMessage(const OccupancyGridMsg& grid, const GridTiling& tiling);

/// Fills MapInfo's grid size and tile index (tile_cells 0 if the grid is not tiled).
void describeTiles(MapInfoMsg& info, const GridTiling& tiling, const std::vector<GridTileEntry>& index,
                   const std::string& overview_sha256);

/// Tile `entry` of a grid with the given resolution and corner: grid.origin = the tile's corner.
MapTileMsg tileMessage(const MapInfoMsg& info, const GridTiling& tiling, const GridTileEntry& entry,
                       std::vector<std::int8_t> cells, float resolution, double origin_x, double origin_y);

/// Writes OUT/grid.pgm (+ grid.yaml) of a tiled grid from its tiles: the image is created with
/// every cell unknown, each tile is checked (publication, index, size, SHA-256 against MapInfo)
/// and written into it at once; finish() checks the whole grid's SHA-256 against
/// MapInfo.grid_sha256 and renames the file into place (atomically). A writer destroyed before
/// finish() removes its temporary file; nothing else is touched.
class TiledGridWriter {
 public:
  /// Throws InputError if `info` does not describe a tiled grid or the file cannot be created.
  TiledGridWriter(const std::filesystem::path& dir, const MapInfoMsg& info);
  ~TiledGridWriter();
  TiledGridWriter(const TiledGridWriter&) = delete;
  TiledGridWriter& operator=(const TiledGridWriter&) = delete;

  /// True if the tile was written; false if it belongs to another publication or was already
  /// written. Throws InputError for a tile of this publication that fails a check.
  bool add(const MapTileMsg& tile);
  bool complete() const { return received_ == expected_.size(); }
  std::size_t received() const { return received_; }
  std::size_t expected() const { return expected_.size(); }
  /// Checks the grid (SHA-256 of all cells) and writes grid.pgm and grid.yaml (resolution of the
  /// tiles, origin = the grid's corner, e.g. the overview's). Returns the SHA-256. Throws
  /// InputError if incomplete or the checksum differs.
  std::string finish(double origin_x, double origin_y);

 private:
  std::filesystem::path dir_, tmp_;
  int fd_ = -1;
  MapInfoMsg info_;  // the publication being assembled
  GridTiling tiling_;
  std::vector<std::uint32_t> keys_;     // MapInfo.tile_indices
  std::vector<std::uint8_t> expected_;  // per entry of keys_: 1 once written
  std::size_t received_ = 0;
  std::size_t header_bytes_ = 0;
  float resolution_ = 0;
  bool finished_ = false;
};

}  // namespace radarslam::dds
