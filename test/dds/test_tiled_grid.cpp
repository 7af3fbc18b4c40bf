// Tiled grids over DDS (dds/grid_tiles.h; docs/dds.md, "Tiled grids"): the reference client's
// writer reassembles the full grid from tiles in any order and rejects a tile MapInfo does not
// vouch for; a map saved with a tiled grid is served as overview + tiles and the client's grid.pgm
// equals the map's layers/grid.pgm byte for byte.
#include <gtest/gtest.h>

#include <random>

#include <radarslam/core/errors.h>
#include <radarslam/dds/cloud_tiles.h>
#include <radarslam/dds/grid_tiles.h>
#include <radarslam/dds/map_messages.h>
#include <radarslam/map/layer_files.h>
#include <radarslam/map/map_io.h>
#include <radarslam/map/sha256.h>

#include "dds_test_util.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using test::Child;

struct TiledGrid {
  std::uint32_t w = 170, h = 120;
  std::vector<std::int8_t> cells;
  GridTiling tiling;
  std::vector<GridTileEntry> index;
  dds::MapInfoMsg info;
  TiledGrid() {
    cells.assign(std::size_t{w} * h, -1);
    std::mt19937 rng(5);
    for (std::uint32_t row = 0; row < 80; ++row)  // the top row of tiles stays unknown
      for (std::uint32_t col = 0; col < w; ++col)
        if (rng() % 3) cells[std::size_t{row} * w + col] = static_cast<std::int8_t>(rng() % 101);
    GridTilingParams p;
    p.tile_cells = 50;
    p.tile_above_cells = 1;
    tiling = gridTiling(w, h, p);
    index = gridTileIndex(cells, tiling);
    info.header = {dds::toTimeMsg(1'700'000'000'000'000'000), "map"};
    info.revision = 3;
    info.grid_sha256 = sha256Hex({reinterpret_cast<const unsigned char*>(cells.data()), cells.size()});
    dds::describeTiles(info, tiling, index, std::string(64, '0'));
  }
  dds::MapTileMsg tile(std::size_t i) const {
    return dds::tileMessage(info, tiling, index[i], tileCells(cells, tiling, index[i].tx, index[i].ty), 0.2f,
                            -10.0, -20.0);
  }
};

TEST(TiledGridWriter, ReassemblesTheGridFromTilesInAnyOrder) {
  test::TempDir tmp;
  const TiledGrid g;
  ASSERT_EQ(g.index.size(), 8u);  // 4 x 3 tiles, the top row unknown
  dds::TiledGridWriter writer(tmp.path(), g.info);
  for (std::size_t i = g.index.size(); i-- > 0;) {
    EXPECT_FALSE(writer.complete());
    EXPECT_TRUE(writer.add(g.tile(i)));
  }
  EXPECT_FALSE(writer.add(g.tile(0)));  // a repeat is ignored
  dds::MapTileMsg other = g.tile(0);
  other.header.stamp.sec += 1;  // another publication
  EXPECT_FALSE(writer.add(other));
  ASSERT_TRUE(writer.complete());
  EXPECT_EQ(writer.finish(-10.0, -20.0), g.info.grid_sha256);
  EXPECT_TRUE(test::readText(tmp.path() / "grid.pgm") == gridPgm(g.cells, g.w, g.h));
  EXPECT_NE(test::readText(tmp.path() / "grid.yaml").find("origin: [-10, -20, 0]"), std::string::npos);
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 2);
}

TEST(TiledGridWriter, RejectsTilesMapInfoDoesNotVouchForAndLeavesNothingBehind) {
  test::TempDir tmp;
  const TiledGrid g;
  {
    dds::TiledGridWriter writer(tmp.path(), g.info);
    dds::MapTileMsg bad = g.tile(1);
    bad.grid.data[0] = static_cast<std::int8_t>(bad.grid.data[0] == 7 ? 8 : 7);
    EXPECT_THROW(writer.add(bad), InputError);
    dds::MapTileMsg unknown = g.tile(1);
    unknown.tile_y = 2;  // an all-unknown tile is never in the index
    EXPECT_THROW(writer.add(unknown), InputError);
    dds::MapTileMsg cut = g.tile(0);
    cut.grid.height -= 1;
    EXPECT_THROW(writer.add(cut), InputError);
    EXPECT_THROW(writer.finish(0, 0), InputError);  // incomplete
  }
  EXPECT_TRUE(fs::is_empty(tmp.path()));  // the temporary image is removed, nothing else written
  dds::MapInfoMsg huge = g.info;          // would make a 4 GB image before any tile arrived
  huge.grid_width = huge.grid_height = 65536;
  EXPECT_THROW(dds::TiledGridWriter(tmp.path(), huge), InputError);
  dds::MapInfoMsg lying = g.info;
  lying.grid_sha256 = std::string(64, 'f');
  {
    dds::TiledGridWriter writer(tmp.path(), lying);
    for (std::size_t i = 0; i < g.index.size(); ++i) writer.add(g.tile(i));
    EXPECT_THROW(writer.finish(0, 0), InputError);
  }
  EXPECT_TRUE(fs::is_empty(tmp.path()));
}

TEST(TiledCloudWriter, AppendsTilesInOrderAndChecksTheWhole) {
  test::TempDir tmp;
  std::vector<std::vector<std::uint8_t>> tiles{std::vector<std::uint8_t>(16 * 3, 1),
                                               std::vector<std::uint8_t>(16, 2)};
  std::vector<std::uint8_t> all = tiles[0];
  all.insert(all.end(), tiles[1].begin(), tiles[1].end());
  dds::MapInfoMsg info;
  info.header = {dds::toTimeMsg(1'700'000'000'000'000'000), "map"};
  info.cloud_tile_count = 2;
  info.cloud_points = 4;
  info.cloud_sha256 = sha256Hex({all.data(), all.size()});
  {
    dds::TiledCloudWriter w(tmp.path(), info);
    EXPECT_TRUE(w.add(dds::cloudTileMessage(info, tiles[0])));
    dds::MapInfoMsg other = info;
    other.header.stamp.sec -= 1;
    EXPECT_FALSE(w.add(dds::cloudTileMessage(other, tiles[1])));  // another publication
    EXPECT_THROW(w.finish(), InputError);                         // incomplete
    EXPECT_TRUE(w.add(dds::cloudTileMessage(info, tiles[1])));
    EXPECT_THROW(w.add(dds::cloudTileMessage(info, tiles[1])), InputError);  // one too many
    EXPECT_EQ(w.finish(), info.cloud_sha256);
  }
  const std::string pcd = test::readText(tmp.path() / "cloud.pcd");
  EXPECT_EQ(pcd, cloudPcdHeader(4) + std::string(all.begin(), all.end()));
  fs::remove(tmp.path() / "cloud.pcd");
  {
    dds::TiledCloudWriter w(tmp.path(), info);  // tiles out of order: the checksum differs
    w.add(dds::cloudTileMessage(info, tiles[1]));
    w.add(dds::cloudTileMessage(info, std::vector<std::uint8_t>(16 * 3, 1)));
    EXPECT_THROW(w.finish(), InputError);
  }
  EXPECT_TRUE(fs::is_empty(tmp.path()));
}

TEST(TiledGrid, ServerSendsOverviewAndTilesClientRebuildsTheGridExactly) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "city";
  MapLayerParams p;
  p.tiling.tile_cells = 64;
  p.tiling.tile_above_cells = 1;
  p.tiling.overview_max_cells = 5000;
  saveMap(test::syntheticMap(6, 400, 40.0, 31), map_dir, {}, p);
  const MapLayersManifest layers = readMapManifest(map_dir).layers.value();
  ASSERT_TRUE(layers.tiling.tiled());
  const unsigned dom = test::testDomainId(20);
  Child server({RADARSLAM_MAP_SERVER, "--map", map_dir.string(), "--domain", std::to_string(dom)},
               tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map 'city' revision 1", 15 * test::timeScale())) << server.err();
  EXPECT_NE(server.err().find(" tiles of 64 cells"), std::string::npos) << server.err();
  const fs::path got = tmp.path() / "got";
  Child client({RADARSLAM_MAP_CLIENT, "-o", got.string(), "--domain", std::to_string(dom), "--timeout",
                std::to_string(20 * test::timeScale())},
               tmp.path() / "client");
  ASSERT_EQ(client.wait(30 * test::timeScale()), 0) << client.err() << server.err();
  EXPECT_TRUE(test::readText(got / "grid.pgm") == test::readText(map_dir / "layers" / "grid.pgm"));
  EXPECT_TRUE(test::readText(got / "overview.pgm") ==
              test::readText(map_dir / "layers" / "grid_overview.pgm"));
  EXPECT_TRUE(fs::exists(got / "grid.yaml") && fs::exists(got / "overview.yaml") &&
              fs::exists(got / "cloud.pcd"));
  EXPECT_NE(test::readText(got / "map_info.yaml").find(layers.grid_cells_sha256), std::string::npos);
  // The cloud came as tiles and was appended in order: the same data as the map's cloud.pcd.
  EXPECT_NE(server.err().find(" tiles"), std::string::npos);
  auto pcdBody = [](const fs::path& file) {
    const std::string t = test::readText(file);
    return t.substr(t.find("DATA binary\n"));
  };
  EXPECT_TRUE(pcdBody(got / "cloud.pcd") == pcdBody(map_dir / "layers" / "cloud.pcd"));
  EXPECT_NE(client.err().find("cloud received"), std::string::npos);
  EXPECT_NE(client.err().find("tiles, written"), std::string::npos) << client.err();
  server.signal(SIGTERM);
  EXPECT_EQ(server.wait(10), 0) << server.err();
}

}  // namespace
}  // namespace radarslam
