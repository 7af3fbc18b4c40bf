#pragma once
// Tiles and overview of a large occupancy grid (issue 16; docs/dds.md, "Tiled grids"). A grid of
// more cells than `tile_above_cells` is published as square tiles of `tile_cells` x `tile_cells`
// cells (the last column and row of tiles cut at the grid's edge), keyed by their index
// (tile_x, tile_y), plus a downsampled overview on /map that any ROS 2 node can show. A tile whose
// cells are all unknown is not published. Cells follow nav_msgs/OccupancyGrid: row 0 = lowest y,
// 0..100 = P(occupied) %, -1 = unknown.
#include <cstdint>
#include <string>
#include <vector>

namespace radarslam {

struct GridTilingParams {
  std::size_t tile_cells = 1024;             ///< tile edge [cells] (1 MiB of cells)
  std::size_t tile_above_cells = 16777216;   ///< grids with more cells are tiled (a 16 MiB /map sample)
  std::size_t overview_max_cells = 4194304;  ///< the overview's cells at most (2048 x 2048)
};

/// The geometry of a tiled grid (all zero `tile_cells` if the grid is not tiled).
struct GridTiling {
  std::uint32_t width = 0, height = 0;  ///< the full-resolution grid [cells]
  std::uint32_t tile_cells = 0;         ///< 0 = not tiled
  std::uint32_t tiles_x = 0, tiles_y = 0;
  std::uint32_t overview_factor = 1;  ///< overview cell = factor x factor grid cells
  std::uint32_t overview_width = 0, overview_height = 0;
  bool tiled() const { return tile_cells > 0; }
  std::uint32_t tileKey(std::uint32_t tx, std::uint32_t ty) const { return ty * tiles_x + tx; }
};
GridTiling gridTiling(std::uint32_t width, std::uint32_t height, const GridTilingParams& params);

/// Cells [col0, col0 + cols) x [row0, row0 + rows) of tile (tx, ty).
struct TileRect {
  std::uint32_t col0 = 0, row0 = 0, cols = 0, rows = 0;
};
TileRect tileRect(const GridTiling& tiling, std::uint32_t tx, std::uint32_t ty);

/// Overview cell = the highest P(occupied) among the known cells of its factor x factor block (an
/// obstacle anywhere in the block stays visible), -1 if none is known. `cells` is width x height.
std::vector<std::int8_t> overviewCells(const std::vector<std::int8_t>& cells, const GridTiling& tiling);

/// The cells of tile (tx, ty) out of the full grid (row 0 = lowest y of the tile).
std::vector<std::int8_t> tileCells(const std::vector<std::int8_t>& cells, const GridTiling& tiling,
                                   std::uint32_t tx, std::uint32_t ty);
/// True if any cell of the tile is known.
bool tileHasKnownCell(const std::vector<std::int8_t>& tile);

/// One published tile: its index and the SHA-256 (hex) of its cells.
struct GridTileEntry {
  std::uint32_t tx = 0, ty = 0;
  std::string sha256;
  bool operator==(const GridTileEntry&) const = default;
};
/// Every tile with a known cell, in publication order (row of tiles by row, west to east).
std::vector<GridTileEntry> gridTileIndex(const std::vector<std::int8_t>& cells, const GridTiling& tiling);
/// The index file (layers/grid_tiles.txt): one line "tx ty sha256" per tile, in order.
std::string gridTileIndexText(const std::vector<GridTileEntry>& tiles);
/// Parses and checks an index (in range, strictly increasing, 64 hex digits); throws InputError(origin).
std::vector<GridTileEntry> parseGridTileIndex(const std::string& text, const GridTiling& tiling,
                                              const std::string& origin);

}  // namespace radarslam
