// Tiles and overview of a large grid (map/grid_tiles.h), and the tiled grid saved with a map
// (layers/grid_overview.pgm, layers/grid_tiles.txt, served tile by tile out of layers/grid.pgm).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "old_format_map.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/grid_tiles.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"
#include "synthetic_map.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;

GridTilingParams smallTiles(std::size_t tile, std::size_t above = 1, std::size_t overview_max = 1u << 22) {
  GridTilingParams p;
  p.tile_cells = tile;
  p.tile_above_cells = above;
  p.overview_max_cells = overview_max;
  return p;
}

// A w x h grid: unknown except a band of known cells in the lower rows and a few obstacles.
std::vector<std::int8_t> sparseGrid(std::uint32_t w, std::uint32_t h, unsigned seed) {
  std::vector<std::int8_t> cells(std::size_t{w} * h, -1);
  std::mt19937 rng(seed);
  for (std::uint32_t row = 0; row < h / 3; ++row)
    for (std::uint32_t col = 0; col < w; ++col)
      cells[std::size_t{row} * w + col] = static_cast<std::int8_t>(rng() % 101);
  return cells;
}

TEST(GridTiles, SmallGridsAreNotTiledLargeOnesAreCutAtTheEdges) {
  EXPECT_FALSE(gridTiling(100, 100, smallTiles(16, 10000)).tiled());
  const GridTiling t = gridTiling(100, 70, smallTiles(32, 7000 - 1));
  ASSERT_TRUE(t.tiled());
  EXPECT_EQ(t.tiles_x, 4u);  // 32 + 32 + 32 + 4
  EXPECT_EQ(t.tiles_y, 3u);  // 32 + 32 + 6
  const TileRect last = tileRect(t, 3, 2);
  EXPECT_EQ(last.col0, 96u);
  EXPECT_EQ(last.cols, 4u);
  EXPECT_EQ(last.row0, 64u);
  EXPECT_EQ(last.rows, 6u);
}

TEST(GridTiles, OverviewFitsItsBudgetAndKeepsEveryObstacle) {
  const std::uint32_t w = 103, h = 61;
  std::vector<std::int8_t> cells(std::size_t{w} * h, -1);
  cells[5 * w + 7] = 100;   // one obstacle
  cells[60 * w + 102] = 0;  // one free cell in the last (cut) block
  const GridTiling t = gridTiling(w, h, smallTiles(16, 1, 500));
  EXPECT_LE(std::uint64_t{t.overview_width} * t.overview_height, 500u);
  EXPECT_EQ(t.overview_width, (w + t.overview_factor - 1) / t.overview_factor);
  const auto o = overviewCells(cells, t);
  const std::uint32_t f = t.overview_factor;
  EXPECT_EQ(o[(5 / f) * t.overview_width + 7 / f], 100);
  EXPECT_EQ(o[(60 / f) * t.overview_width + 102 / f], 0);
  EXPECT_EQ(std::count(o.begin(), o.end(), -1), static_cast<long>(o.size()) - 2);
}

TEST(GridTiles, TilesWithAKnownCellReassembleTheGridExactly) {
  const std::uint32_t w = 150, h = 90;
  const auto cells = sparseGrid(w, h, 1);
  const GridTiling t = gridTiling(w, h, smallTiles(40));
  const auto index = gridTileIndex(cells, t);
  // Rows of tiles above the known band (row >= 30) hold no known cell: not in the index.
  EXPECT_EQ(index.size(), std::size_t{t.tiles_x} * 1);
  std::vector<std::int8_t> rebuilt(cells.size(), -1);
  for (const auto& e : index) {
    const auto tile = tileCells(cells, t, e.tx, e.ty);
    EXPECT_EQ(sha256Hex({reinterpret_cast<const unsigned char*>(tile.data()), tile.size()}), e.sha256);
    const TileRect r = tileRect(t, e.tx, e.ty);
    for (std::uint32_t row = 0; row < r.rows; ++row)
      std::copy_n(tile.data() + std::size_t{row} * r.cols, r.cols,
                  rebuilt.data() + std::size_t{r.row0 + row} * w + r.col0);
  }
  EXPECT_TRUE(rebuilt == cells);
  EXPECT_EQ(parseGridTileIndex(gridTileIndexText(index), t, "x"), index);
}

TEST(GridTiles, HostileIndexIsRejectedNamingTheLine) {
  const GridTiling t = gridTiling(100, 100, smallTiles(32));
  const std::string sha(64, 'a');
  for (const std::string& bad : {"4 0 " + sha + "\n",                   // tx out of range
                                 "0 0 " + sha + "\n0 0 " + sha + "\n",  // repeated
                                 "1 0 " + sha + "\n0 0 " + sha + "\n",  // out of order
                                 "0 0 " + sha.substr(1) + "\n",         // short hash
                                 "0 0 " + sha + " extra\n", "-1 0 " + sha + "\n", "zero 0 " + sha + "\n"}) {
    try {
      parseGridTileIndex(bad, t, "grid_tiles.txt");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("grid_tiles.txt"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("line"), std::string::npos);
    }
  }
}

MapLayerParams tiledLayers() {
  MapLayerParams p;
  p.tiling = smallTiles(64, 1, 4000);
  return p;
}

TEST(GridTiles, SavedTiledGridServesTheSameCellsTileByTile) {
  test::TempDir tmp;
  saveMap(test::syntheticMap(5, 400), tmp / "m", {}, tiledLayers());
  const MapLayersManifest layers = readMapManifest(tmp / "m").layers.value();
  ASSERT_TRUE(layers.tiling.tiled());
  EXPECT_EQ(layers.files.size(), 7u);
  const auto cells = readGridLayer(tmp / "m", layers);
  EXPECT_TRUE(readGridOverviewLayer(tmp / "m", layers) == overviewCells(cells, layers.tiling));
  const auto index = readGridTileIndexLayer(tmp / "m", layers);
  EXPECT_EQ(index, gridTileIndex(cells, layers.tiling));
  ASSERT_GT(index.size(), 1u);
  std::size_t n = 0;
  forEachGridTileLayer(tmp / "m", layers, index,
                       [&](const GridTileEntry& e, const std::vector<std::int8_t>& t) {
                         EXPECT_EQ(e, index[n++]);
                         EXPECT_TRUE(t == tileCells(cells, layers.tiling, e.tx, e.ty));
                       });
  EXPECT_EQ(n, index.size());
  // Reloaded as it was saved (parameters and tiling come back from the manifest).
  EXPECT_EQ(layers.params.tiling.tile_cells, 64u);
  EXPECT_EQ(layers.tiling.overview_factor,
            gridTiling(layers.grid_width, layers.grid_height, tiledLayers().tiling).overview_factor);
}

TEST(GridTiles, SavedTiledCloudIsSortedByTileAndServedTileByTile) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap(6, 400);
  saveMap(map, tmp / "m", {}, tiledLayers());
  const MapLayersManifest layers = readMapManifest(tmp / "m").layers.value();
  const auto index = readCloudTileIndexLayer(tmp / "m", layers);
  ASSERT_GT(index.size(), 1u);
  // The same points as the keyframes give, as a multiset, each in the tile it lies in.
  std::vector<std::uint8_t> expected = cloudPayload(map);
  std::vector<std::uint8_t> got;
  const double res = layers.params.grid.resolution_m;
  forEachCloudTileLayer(
      tmp / "m", layers, index, [&](const CloudTileEntry& e, const std::vector<std::uint8_t>& d) {
        ASSERT_EQ(d.size(), e.count * 16);
        for (std::size_t i = 0; i < e.count; ++i) {
          float xy[2];
          std::memcpy(xy, d.data() + 16 * i, sizeof xy);
          EXPECT_EQ(
              cloudTileKey(layers.tiling, res, layers.grid_origin_x, layers.grid_origin_y, xy[0], xy[1]),
              layers.tiling.tileKey(e.tx, e.ty));
        }
        got.insert(got.end(), d.begin(), d.end());
      });
  EXPECT_EQ(sha256Hex({got.data(), got.size()}), layers.cloud_data_sha256);
  auto records = [](const std::vector<std::uint8_t>& d) {
    std::vector<std::string> r;
    for (std::size_t i = 0; i < d.size(); i += 16)
      r.emplace_back(reinterpret_cast<const char*>(d.data() + i), 16);
    std::sort(r.begin(), r.end());
    return r;
  };
  EXPECT_TRUE(records(got) == records(expected));
  // And in order: the keyframe-order payload sorted stably by tile, byte for byte.
  std::vector<std::size_t> order(expected.size() / 16);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto keyOf = [&](std::size_t i) {
    float xy[2];
    std::memcpy(xy, expected.data() + 16 * i, sizeof xy);
    return cloudTileKey(layers.tiling, res, layers.grid_origin_x, layers.grid_origin_y, xy[0], xy[1]);
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return keyOf(a) < keyOf(b); });
  std::vector<std::uint8_t> stably_sorted;
  for (const std::size_t i : order)
    stably_sorted.insert(stably_sorted.end(), expected.begin() + 16 * i, expected.begin() + 16 * (i + 1));
  EXPECT_TRUE(got == stably_sorted);
  const TiledCloud direct =
      tiledCloudPayload(map, layers.tiling, res, layers.grid_origin_x, layers.grid_origin_y);
  EXPECT_TRUE(direct.data == stably_sorted);
  EXPECT_EQ(direct.tiles, index);
  // A hostile index: ranges that do not add up are rejected naming the file.
  const std::string text = cloudTileIndexText(index);
  EXPECT_THROW(parseCloudTileIndex(text, layers.tiling, layers.cloud_points + 1, "c"), InputError);
  EXPECT_THROW(parseCloudTileIndex(text.substr(text.find('\n') + 1), layers.tiling, layers.cloud_points, "c"),
               InputError);
}

TEST(GridTiles, CorruptTileIsAnErrorNamingTheFileAndTheTile) {
  test::TempDir tmp;
  saveMap(test::syntheticMap(6, 400), tmp / "m", {}, tiledLayers());
  const MapLayersManifest layers = readMapManifest(tmp / "m").layers.value();
  const auto index = readGridTileIndexLayer(tmp / "m", layers);
  ASSERT_FALSE(index.empty());
  // Flip one pixel of the first known cell of the last tile to another valid value.
  const GridTileEntry& e = index.back();
  const TileRect r = tileRect(layers.tiling, e.tx, e.ty);
  const fs::path grid = tmp / "m" / "layers" / "grid.pgm";
  std::string bytes = test::readFileBytes(grid);
  const std::size_t header = bytes.size() - std::size_t{layers.grid_width} * layers.grid_height;
  bool flipped = false;
  for (std::uint32_t row = 0; row < r.rows && !flipped; ++row)
    for (std::uint32_t col = 0; col < r.cols && !flipped; ++col) {
      const std::size_t at =
          header + std::size_t{layers.grid_height - 1 - (r.row0 + row)} * layers.grid_width + r.col0 + col;
      if (static_cast<unsigned char>(bytes[at]) != gridPixel(-1)) {
        bytes[at] =
            static_cast<char>(gridPixel(gridCellOfPixel(static_cast<unsigned char>(bytes[at])) == 0 ? 1 : 0));
        flipped = true;
      }
    }
  ASSERT_TRUE(flipped);
  test::writeFileBytes(grid, bytes);
  try {
    forEachGridTileLayer(tmp / "m", layers, index,
                         [](const GridTileEntry&, const std::vector<std::int8_t>&) {});
    ADD_FAILURE() << "corrupt tile accepted";
  } catch (const InputError& err) {
    const std::string msg = err.what();
    EXPECT_NE(msg.find(grid.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("tile (" + std::to_string(e.tx) + ", " + std::to_string(e.ty) + ")"),
              std::string::npos)
        << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
}

TEST(GridTiles, ManifestWithoutTilingKeysIsNeverTiled) {
  test::TempDir tmp;
  MapLayerParams p;
  p.tiling = smallTiles(64, 1u << 30);  // not tiled: the manifest looks like an older one
  saveMap(test::syntheticMap(4, 300), tmp / "m", {}, p);
  std::string manifest = test::readFileBytes(tmp / "m" / "manifest.yaml");
  for (const char* key : {"  grid_tile_cells:", "  grid_tile_above_cells:", "  grid_overview_max_cells:"}) {
    const auto at = manifest.find(key);
    ASSERT_NE(at, std::string::npos);
    manifest.erase(at, manifest.find('\n', at) + 1 - at);
  }
  test::writeFileBytes(tmp / "m" / "manifest.yaml", manifest);
  const auto layers = readMapManifest(tmp / "m").layers;
  ASSERT_TRUE(layers.has_value());
  EXPECT_FALSE(layers->tiling.tiled());
  EXPECT_EQ(layers->files.size(), 4u);
}

}  // namespace
}  // namespace radarslam
