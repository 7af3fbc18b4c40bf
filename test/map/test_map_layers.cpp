// The layers saved with a map (map/map_layers.h, map/layer_files.h): listed in the manifest with
// matching checksums, equal to what the exporters build from the keyframes, corrupt or hostile
// layer files rejected naming the file, older maps without layers still loading.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <sstream>
#include <string>

#include "old_format_map.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/octomap_slab.h"
#include "radarslam/map/sha256.h"
#include "synthetic_map.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using test::readFileBytes;
using test::writeFileBytes;

// Runs f() expecting an InputError with one line that contains each of `parts`.
template <class F>
void expectInputError(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
}

MapLayersManifest saveWithLayers(const KeyframeMap& map, const fs::path& dir, const MapLayerParams& p = {}) {
  saveMap(map, dir, {}, p);
  const MapManifestSummary s = readMapManifest(dir);
  EXPECT_EQ(s.format_version, kMapFormatVersion);
  EXPECT_TRUE(s.layers.has_value());
  return s.layers.value_or(MapLayersManifest{});
}

TEST(MapLayers, SaveWritesEveryLayerWithItsChecksumAndParameters) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap();
  MapLayerParams p;
  p.grid.resolution_m = 0.25;
  p.octomap.resolution_m = 0.25;
  const MapLayersManifest layers = saveWithLayers(map, tmp / "m", p);
  ASSERT_EQ(layers.files.size(), 4u);
  for (const auto& f : layers.files) {
    const std::string bytes = readFileBytes(tmp / "m" / f.name);
    EXPECT_EQ(bytes.size(), f.bytes) << f.name;
    EXPECT_EQ(sha256Hex(bytes), f.sha256) << f.name;
  }
  EXPECT_EQ(layers.params.grid.resolution_m, 0.25);
  EXPECT_EQ(layers.params.octomap.resolution_m, 0.25);
  const OccupancyRaster raster = buildOccupancy(map, p.grid);
  EXPECT_EQ(layers.grid_width, static_cast<std::uint32_t>(raster.width));
  EXPECT_EQ(layers.grid_height, static_cast<std::uint32_t>(raster.height));
  EXPECT_EQ(layers.grid_origin_x, raster.x_min);
  EXPECT_EQ(layers.grid_origin_y, raster.y_min);
  const auto cells = occupancyCells(raster);
  EXPECT_EQ(layers.grid_cells_sha256,
            sha256Hex({reinterpret_cast<const unsigned char*>(cells.data()), cells.size()}));
  // The keyframes are still there and load as before.
  const KeyframeMap back = loadMap(tmp / "m");
  EXPECT_EQ(back.keyframes.size(), map.keyframes.size());
  EXPECT_EQ(back.meta.format_version, kMapFormatVersion);
}

TEST(MapLayers, LayerFilesHoldExactlyWhatTheExportersBuild) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap(6, 300);
  const MapLayersManifest layers = saveWithLayers(map, tmp / "m");
  const OccupancyRaster raster = buildOccupancy(map);
  EXPECT_EQ(readGridLayer(tmp / "m", layers), occupancyCells(raster));

  std::uint64_t points = 0;
  const auto cloud = readCloudLayer(tmp / "m", layers, points);
  exportPointCloud(map, tmp / "exp", "cloud");
  const std::string pcd = readFileBytes(tmp / "exp" / "cloud.pcd");
  const std::string body = pcd.substr(pcd.find("DATA binary\n") + 12);
  EXPECT_EQ(points, 6u * 300u);
  EXPECT_EQ(std::string(cloud.begin(), cloud.end()), body);

  OctomapSlabParams sp;
  sp.full_data = false;
  const auto octo = readOctomapLayer(tmp / "m", layers);
  EXPECT_EQ(std::string(octo.begin(), octo.end()), encodeOctomapSlab(raster, sp).binary_data);
  // The grid image is a plain PGM of the size the manifest gives (ROS map_server reads it).
  EXPECT_EQ(readFileBytes(tmp / "m" / "layers" / "grid.pgm").rfind("P5\n", 0), 0u);
  EXPECT_NE(readFileBytes(tmp / "m" / "layers" / "grid.yaml").find("image: grid.pgm\n"), std::string::npos);
}

TEST(MapLayers, CorruptLayerFileIsRejectedNamingTheFile) {
  test::TempDir tmp;
  const MapLayersManifest layers = saveWithLayers(test::syntheticMap(), tmp / "m");
  const fs::path cloud = tmp / "m" / "layers" / "cloud.pcd";
  std::string bytes = readFileBytes(cloud);
  bytes[bytes.size() - 3] ^= 0x40;
  writeFileBytes(cloud, bytes);
  std::uint64_t n = 0;
  expectInputError([&] { readCloudLayer(tmp / "m", layers, n); }, {cloud.string(), "checksum mismatch"});

  const fs::path grid = tmp / "m" / "layers" / "grid.pgm";
  writeFileBytes(grid, readFileBytes(grid) + "x");
  expectInputError([&] { readGridLayer(tmp / "m", layers); }, {grid.string(), "size mismatch"});

  fs::remove(tmp / "m" / "layers" / "map.bt");
  expectInputError([&] { readOctomapLayer(tmp / "m", layers); }, {"layers/map.bt", "missing"});
}

TEST(MapLayers, HostileLayerWithAMatchingChecksumIsRejected) {
  test::TempDir tmp;
  MapLayersManifest layers = saveWithLayers(test::syntheticMap(), tmp / "m");
  // A pixel value the grid layer never holds, with the manifest's checksum made to match.
  const fs::path grid = tmp / "m" / "layers" / "grid.pgm";
  std::string bytes = readFileBytes(grid);
  bytes[bytes.size() - 1] = static_cast<char>(17);
  writeFileBytes(grid, bytes);
  for (auto& f : layers.files)
    if (f.key == "grid") f.sha256 = sha256Hex(bytes);
  expectInputError([&] { readGridLayer(tmp / "m", layers); }, {grid.string(), "pixel value 17"});

  // A PCD whose header announces other fields.
  const fs::path cloud = tmp / "m" / "layers" / "cloud.pcd";
  std::string pcd = readFileBytes(cloud);
  pcd.replace(pcd.find("FIELDS x y z intensity"), 22, "FIELDS x y z rgbacolor");
  writeFileBytes(cloud, pcd);
  for (auto& f : layers.files)
    if (f.key == "cloud") f.sha256 = sha256Hex(pcd), f.bytes = pcd.size();
  std::uint64_t n = 0;
  expectInputError([&] { readCloudLayer(tmp / "m", layers, n); }, {cloud.string(), "PCD header"});
}

TEST(MapLayers, MalformedLayersSectionIsAnErrorNamingTheManifest) {
  test::TempDir tmp;
  saveWithLayers(test::syntheticMap(), tmp / "m");
  const fs::path mp = tmp / "m" / "manifest.yaml";
  std::string text = readFileBytes(mp);
  text.replace(text.find("name: \"layers/map.bt\""), 21, "name: \"../../etc/pwd\"");
  writeFileBytes(mp, text);
  expectInputError([&] { readMapManifest(tmp / "m"); }, {mp.string(), "layers.files.octomap"});
}

TEST(MapLayers, Format1MapStillLoadsAndHasNoLayers) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap();
  saveWithLayers(map, tmp / "m");
  test::downgradeToFormat1(tmp / "m");
  const MapManifestSummary s = readMapManifest(tmp / "m");
  EXPECT_EQ(s.format_version, 1u);
  EXPECT_FALSE(s.layers.has_value());
  EXPECT_EQ(s.keyframes, map.keyframes.size());
  const KeyframeMap back = loadMap(tmp / "m");
  EXPECT_EQ(back.meta.format_version, 1u);
  EXPECT_EQ(back.keyframes.size(), map.keyframes.size());
  EXPECT_EQ(back.edges, map.edges);
}

TEST(MapLayers, OctreeStreamWalkCountsTheNodesOctomapReads) {
  const OccupancyRaster raster = buildOccupancy(test::syntheticMap(6, 300));
  const OctomapSlab slab = encodeOctomapSlab(raster);
  octomap::OcTree tree(raster.resolution);
  std::istringstream in(slab.binary_data, std::ios::binary);
  ASSERT_TRUE(tree.readBinaryData(in));
  EXPECT_EQ(octreeBinaryNodeCount(slab.binary_data), std::optional<std::size_t>(tree.size()));
  EXPECT_EQ(octreeBinaryNodeCount(slab.binary_data), std::optional<std::size_t>(slab.nodes));
  EXPECT_FALSE(octreeBinaryNodeCount(slab.binary_data.substr(0, slab.binary_data.size() - 1)));
  EXPECT_FALSE(octreeBinaryNodeCount(slab.binary_data + "x"));
  EXPECT_FALSE(octreeBinaryNodeCount(std::string(40, '\xff')));  // inner nodes all the way down
  EXPECT_EQ(octreeBinaryNodeCount(""), std::optional<std::size_t>(0));
}

TEST(MapLayers, SaveWithoutLayersListsNone) {
  test::TempDir tmp;
  saveMap(test::syntheticMap(), tmp / "m");
  EXPECT_FALSE(readMapManifest(tmp / "m").layers.has_value());
  EXPECT_FALSE(fs::exists(tmp / "m" / "layers"));
}

TEST(MapLayers, ParametersComeFromTheMapLayersSection) {
  MapLayerParams p;
  loadParams(
      YamlParams::fromText("grid_resolution_m: 0.5\noctomap_fill: point_rays\noctomap_resolution_m: 1\n"), p);
  EXPECT_EQ(p.grid.resolution_m, 0.5);
  EXPECT_EQ(p.octomap.fill, OctomapExportParams::Fill::point_rays);
  EXPECT_EQ(p.octomap.resolution_m, 1.0);
  expectInputError([&] { loadParams(YamlParams::fromText("grid_resolution_m: 0\n", "x.yaml"), p); },
                   {"x.yaml", "grid_resolution_m"});
  expectInputError([&] { loadParams(YamlParams::fromText("octomap_fill: voxels\n", "x.yaml"), p); },
                   {"x.yaml", "octomap_fill"});
}

}  // namespace
}  // namespace radarslam
