// The map server publishing the layers saved with the map (map/map_layers.h): the messages read
// from the layer files equal the ones it used to build from the keyframes; a late joiner gets
// them; a format-1 map is still served (built, with a warning); a corrupt layer file is a
// one-line error naming it; a changed map is reloaded from its new layers.
#include <gtest/gtest.h>

#include <radarslam/dds/map_messages.h>
#include <radarslam/map/layer_files.h>
#include <radarslam/map/map_io.h>
#include <radarslam/map/sha256.h>

#include "dds_test_util.h"
#include "old_format_map.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using test::Child;

const std::string kServer = RADARSLAM_MAP_SERVER;
const std::string kClient = RADARSLAM_MAP_CLIENT;

std::string yamlValue(const std::string& text, const std::string& key) {
  const auto pos = text.find(key + ": ");
  if (pos == std::string::npos) return "";
  std::string v = text.substr(pos + key.size() + 2, text.find('\n', pos) - pos - key.size() - 2);
  if (v.size() >= 2 && v.front() == '"') v = v.substr(1, v.size() - 2);
  return v;
}

std::vector<std::string> serverArgs(const fs::path& map, unsigned domain,
                                    std::vector<std::string> extra = {}) {
  std::vector<std::string> a{kServer, "--map", map.string(), "--domain", std::to_string(domain)};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}
std::vector<std::string> clientArgs(const fs::path& out, unsigned domain,
                                    std::vector<std::string> extra = {}) {
  std::vector<std::string> a{kClient,     "-o", out.string(), "--domain", std::to_string(domain),
                             "--timeout", "15"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

// What the server used to publish: the layers built from the keyframes (default parameters).
std::string builtGridSha(const KeyframeMap& map) {
  return dds::gridSha256(dds::gridMessage(buildOccupancy(map), 0));
}

TEST(SavedLayers, MessagesFromTheLayerFilesEqualTheOnesBuiltFromTheKeyframes) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap(5, 400, 40.0, 11);
  saveMap(map, tmp / "m", {}, MapLayerParams{});
  const auto layers = readMapManifest(tmp / "m").layers;
  ASSERT_TRUE(layers.has_value());
  const StampNs t = 1'700'000'000'000'000'000;
  const OccupancyRaster raster = buildOccupancy(map);
  EXPECT_TRUE(dds::gridMessage(tmp / "m", *layers, t) == dds::gridMessage(raster, t));
  EXPECT_TRUE(dds::cloudMessage(tmp / "m", *layers, t) == dds::cloudMessage(map, t));
  EXPECT_TRUE(dds::octomapMessage(tmp / "m", *layers, t) == dds::octomapMessage(raster, t));
  EXPECT_EQ(dds::gridSha256(dds::gridMessage(tmp / "m", *layers, t)), builtGridSha(map));
}

TEST(SavedLayers, ServerPublishesTheSavedLayersAndReloadsNewOnes) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "campus";
  const KeyframeMap map = test::syntheticMap(6, 300, 40.0, 12);
  saveMap(map, map_dir, {}, MapLayerParams{});
  const unsigned dom = test::testDomainId(13);

  Child server(serverArgs(map_dir, dom, {"--poll", "0.2"}), tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map 'campus' revision 1", 15)) << server.err();
  EXPECT_NE(server.err().find("saved layers"), std::string::npos) << server.err();
  EXPECT_EQ(server.err().find("map-layers"), std::string::npos) << server.err();
  Child client(clientArgs(tmp.path() / "got", dom), tmp.path() / "client");
  ASSERT_EQ(client.wait(20), 0) << client.err();
  const std::string info = test::readText(tmp.path() / "got" / "map_info.yaml");
  EXPECT_EQ(yamlValue(info, "grid_sha256"), builtGridSha(map));
  EXPECT_EQ(yamlValue(info, "keyframes"), "6");
  EXPECT_EQ(yamlValue(info, "format_version"), std::to_string(kMapFormatVersion));
  // The client's files hold what the map directory holds, byte for byte (the PCD's comment line
  // differs).
  auto pcdBody = [](const fs::path& p) {
    const std::string t = test::readText(p);
    return t.substr(t.find("DATA binary\n"));
  };
  EXPECT_TRUE(pcdBody(tmp.path() / "got" / "cloud.pcd") == pcdBody(map_dir / "layers" / "cloud.pcd"));
  EXPECT_TRUE(test::readText(tmp.path() / "got" / "map.bt") == test::readText(map_dir / "layers" / "map.bt"));
  EXPECT_TRUE(test::readText(tmp.path() / "got" / "grid.pgm") ==
              test::readText(map_dir / "layers" / "grid.pgm"));

  // A new map with its layers swapped in while the server runs.
  const KeyframeMap map_b = test::syntheticMap(4, 250, 35.0, 13);
  saveMap(map_b, map_dir, {}, MapLayerParams{});
  const std::string sha_b = builtGridSha(map_b);
  Child second(clientArgs(tmp.path() / "b", dom, {"--expect-grid-sha256", sha_b}), tmp.path() / "b");
  ASSERT_EQ(second.wait(20), 0) << second.err() << server.err();
  EXPECT_EQ(yamlValue(test::readText(tmp.path() / "b" / "map_info.yaml"), "revision"), "2");
  server.signal(SIGTERM);
  EXPECT_EQ(server.wait(10), 0) << server.err();
}

TEST(SavedLayers, Format1MapIsServedFromItsKeyframesWithAWarning) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "old";
  const KeyframeMap map = test::syntheticMap(4, 200, 30.0, 14);
  saveMap(map, map_dir, {}, MapLayerParams{});
  test::downgradeToFormat1(map_dir);
  const unsigned dom = test::testDomainId(14);
  Child server(serverArgs(map_dir, dom), tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map 'old' revision 1", 15)) << server.err();
  EXPECT_NE(server.err().find("radarslam map-layers"), std::string::npos) << server.err();
  Child client(clientArgs(tmp.path() / "got", dom), tmp.path() / "client");
  ASSERT_EQ(client.wait(20), 0) << client.err();
  const std::string info = test::readText(tmp.path() / "got" / "map_info.yaml");
  EXPECT_EQ(yamlValue(info, "grid_sha256"), builtGridSha(map));
  EXPECT_EQ(yamlValue(info, "format_version"), "1");
}

TEST(SavedLayers, CorruptLayerFileIsAOneLineErrorNamingIt) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "bad";
  saveMap(test::syntheticMap(3, 100, 20.0, 15), map_dir, {}, MapLayerParams{});
  const fs::path grid = map_dir / "layers" / "grid.pgm";
  std::string bytes = test::readFileBytes(grid);
  bytes[bytes.size() / 2] ^= 0x01;
  test::writeFileBytes(grid, bytes);
  Child server(serverArgs(map_dir, test::testDomainId(15)), tmp.path() / "server");
  EXPECT_EQ(server.wait(15), 1) << server.err();
  const std::string err = server.err();
  const std::string line = err.substr(err.find("radarslam-map-server: error:"));
  EXPECT_NE(line.find(grid.string()), std::string::npos) << err;
  EXPECT_NE(line.find("checksum mismatch"), std::string::npos) << err;
  EXPECT_EQ(line.find('\n'), line.size() - 1) << err;
}

}  // namespace
}  // namespace radarslam
