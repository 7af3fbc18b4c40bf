// Tiles and overview of a large occupancy grid (map/grid_tiles.h).
#include "radarslam/map/grid_tiles.h"

#include <algorithm>
#include <sstream>

#include "radarslam/core/errors.h"
#include "radarslam/map/sha256.h"

namespace radarslam {

namespace {
std::uint32_t ceilDiv(std::uint64_t a, std::uint64_t b) {
  return static_cast<std::uint32_t>((a + b - 1) / b);
}
}  // namespace

GridTiling gridTiling(std::uint32_t width, std::uint32_t height, const GridTilingParams& p) {
  GridTiling t;
  t.width = width;
  t.height = height;
  t.overview_width = width;
  t.overview_height = height;
  const std::uint64_t cells = std::uint64_t{width} * height;
  if (cells <= p.tile_above_cells || p.tile_cells == 0) return t;
  t.tile_cells = static_cast<std::uint32_t>(p.tile_cells);
  t.tiles_x = ceilDiv(width, t.tile_cells);
  t.tiles_y = ceilDiv(height, t.tile_cells);
  // Smallest integer factor whose overview fits overview_max_cells.
  std::uint32_t f = 1;
  while (std::uint64_t{ceilDiv(width, f)} * ceilDiv(height, f) >
         std::max<std::size_t>(1, p.overview_max_cells))
    ++f;
  t.overview_factor = f;
  t.overview_width = ceilDiv(width, f);
  t.overview_height = ceilDiv(height, f);
  return t;
}

TileRect tileRect(const GridTiling& t, std::uint32_t tx, std::uint32_t ty) {
  TileRect r;
  r.col0 = tx * t.tile_cells;
  r.row0 = ty * t.tile_cells;
  r.cols = std::min(t.tile_cells, t.width - r.col0);
  r.rows = std::min(t.tile_cells, t.height - r.row0);
  return r;
}

std::vector<std::int8_t> overviewCells(const std::vector<std::int8_t>& cells, const GridTiling& t) {
  const std::uint32_t f = t.overview_factor;
  std::vector<std::int8_t> out(std::size_t{t.overview_width} * t.overview_height, std::int8_t{-1});
  for (std::uint32_t row = 0; row < t.height; ++row) {
    const std::int8_t* src = cells.data() + std::size_t{row} * t.width;
    std::int8_t* dst = out.data() + std::size_t{row / f} * t.overview_width;
    for (std::uint32_t col = 0; col < t.width; ++col) {
      std::int8_t& o = dst[col / f];
      if (src[col] > o) o = src[col];  // unknown (-1) never wins over a known cell
    }
  }
  return out;
}

std::vector<std::int8_t> tileCells(const std::vector<std::int8_t>& cells, const GridTiling& t,
                                   std::uint32_t tx, std::uint32_t ty) {
  const TileRect r = tileRect(t, tx, ty);
  std::vector<std::int8_t> out(std::size_t{r.cols} * r.rows);
  for (std::uint32_t row = 0; row < r.rows; ++row)
    std::copy_n(cells.data() + std::size_t{r.row0 + row} * t.width + r.col0, r.cols,
                out.data() + std::size_t{row} * r.cols);
  return out;
}

bool tileHasKnownCell(const std::vector<std::int8_t>& tile) {
  return std::any_of(tile.begin(), tile.end(), [](std::int8_t c) { return c >= 0; });
}

std::vector<GridTileEntry> gridTileIndex(const std::vector<std::int8_t>& cells, const GridTiling& t) {
  std::vector<GridTileEntry> index;
  for (std::uint32_t ty = 0; ty < t.tiles_y; ++ty)
    for (std::uint32_t tx = 0; tx < t.tiles_x; ++tx) {
      const std::vector<std::int8_t> tile = tileCells(cells, t, tx, ty);
      if (tileHasKnownCell(tile))
        index.push_back(
            {tx, ty, sha256Hex({reinterpret_cast<const unsigned char*>(tile.data()), tile.size()})});
    }
  return index;
}

std::string gridTileIndexText(const std::vector<GridTileEntry>& tiles) {
  std::string out;
  for (const auto& e : tiles)
    out += std::to_string(e.tx) + " " + std::to_string(e.ty) + " " + e.sha256 + "\n";
  return out;
}

std::vector<GridTileEntry> parseGridTileIndex(const std::string& text, const GridTiling& t,
                                              const std::string& origin) {
  std::vector<GridTileEntry> out;
  std::istringstream in(text);
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    std::istringstream ls(line);
    long long tx = -1, ty = -1;
    GridTileEntry e;
    std::string rest;
    if (!(ls >> tx >> ty >> e.sha256) || (ls >> rest) || tx < 0 || ty < 0 || tx >= t.tiles_x ||
        ty >= t.tiles_y || !isSha256Hex(e.sha256))
      throw InputError(origin, "line " + std::to_string(n) + ": expected 'tx ty sha256' of a tile in 0.." +
                                   std::to_string(t.tiles_x) + " x 0.." + std::to_string(t.tiles_y));
    e.tx = static_cast<std::uint32_t>(tx);
    e.ty = static_cast<std::uint32_t>(ty);
    if (!out.empty() && t.tileKey(e.tx, e.ty) <= t.tileKey(out.back().tx, out.back().ty))
      throw InputError(origin, "line " + std::to_string(n) + ": tiles out of order or repeated");
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace radarslam
