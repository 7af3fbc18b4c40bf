// Fuzz target: the tile indexes of a tiled map (layers/grid_tiles.txt and layers/cloud_tiles.txt,
// map/grid_tiles.h, map/cloud_tiles.h). A hostile map can carry any index whose SHA-256 it lists
// in its manifest, so the parsers must reject every malformed one with an InputError. The first
// input byte picks the parser and the grid (width, height in tiles; cloud point count); the rest
// is the index text.
#include <string>

#include "fuzz_common.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/cloud_tiles.h"
#include "radarslam/map/grid_tiles.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t pick = data[0];
  radarslam::GridTilingParams p;
  p.tile_cells = 16;
  p.tile_above_cells = 1;
  // 1..8 x 1..4 tiles of 16 cells, the last column/row cut.
  const auto tiling = radarslam::gridTiling(16 * (1 + (pick & 7)) - 3, 16 * (1 + ((pick >> 3) & 3)) - 5, p);
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    if (pick & 0x80) {
      const auto tiles =
          radarslam::parseCloudTileIndex(text, tiling, (pick & 0x40) ? 1000 : 7, "cloud_tiles.txt");
      std::uint64_t next = 0;  // what the parser promises: contiguous ranges covering every point
      for (const auto& t : tiles) {
        if (t.first != next || t.count == 0 || t.tx >= tiling.tiles_x || t.ty >= tiling.tiles_y)
          __builtin_trap();
        next += t.count;
      }
      if (!tiles.empty() && next != ((pick & 0x40) ? 1000u : 7u)) __builtin_trap();
    } else {
      const auto tiles = radarslam::parseGridTileIndex(text, tiling, "grid_tiles.txt");
      for (std::size_t i = 0; i < tiles.size(); ++i)
        if (tiles[i].tx >= tiling.tiles_x || tiles[i].ty >= tiling.tiles_y ||
            (i > 0 &&
             tiling.tileKey(tiles[i].tx, tiles[i].ty) <= tiling.tileKey(tiles[i - 1].tx, tiles[i - 1].ty)))
          __builtin_trap();
    }
  } catch (const radarslam::InputError&) {
  }
  return 0;
}
