// `radarslam map-layers MAP`: rebuilds the layers of a format-1 map in place (atomically, keeping
// the map's other files), --help, and one-line errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_run.h"
#include "old_format_map.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using test::runCli;

// A small map: two keyframes seeing a ring of points.
KeyframeMap ringMap() {
  KeyframeMap map;
  map.meta.sensor = {400, 3768, 0.0438, 0.1};
  map.meta.created_ns = 1'700'000'000'000'000'000;
  for (int k = 0; k < 2; ++k) {
    Keyframe kf;
    kf.id = k + 1;
    kf.stamp_ns = 1'500'000'000'000'000'000 + k * 250'000'000LL;
    kf.pose = {2.0 * k, 0.0, 0.1 * k};
    for (int i = 0; i < 90; ++i)
      kf.points.push_back(
          {static_cast<float>(15 * std::cos(i * 0.07)), static_cast<float>(15 * std::sin(i * 0.07)), 100.f});
    map.keyframes.push_back(kf);
  }
  return map;
}

std::string oneLine(const std::string& err) {
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
  return err;
}

TEST(CliMapLayers, RebuildsTheLayersOfAFormat1MapKeepingItsOtherFiles) {
  test::TempDir tmp;
  const fs::path dir = tmp / "old";
  const KeyframeMap map = ringMap();
  saveMap(map, dir);
  test::downgradeToFormat1(dir);
  test::writeFileBytes(dir / "trajectory.tum", "1 0 0 0 0 0 0 1\n");
  fs::create_directories(dir / "exports");
  test::writeFileBytes(dir / "exports" / "mine.txt", "not radarslam's\n");
  ASSERT_FALSE(readMapManifest(dir).layers.has_value());

  const auto r = runCli("map-layers '" + dir.string() + "' --resolution 0.5", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("format 1 -> 2"), std::string::npos) << r.out;
  const MapManifestSummary s = readMapManifest(dir);
  EXPECT_EQ(s.format_version, kMapFormatVersion);
  ASSERT_TRUE(s.layers.has_value());
  EXPECT_EQ(s.layers->params.grid.resolution_m, 0.5);
  for (const auto& f : s.layers->files)
    EXPECT_EQ(sha256Hex(test::readFileBytes(dir / f.name)), f.sha256) << f.name;
  EXPECT_EQ(readGridLayer(dir, *s.layers), occupancyCells(buildOccupancy(map, s.layers->params.grid)));
  // Same map, same creation time; the files it did not write are still there.
  const KeyframeMap back = loadMap(dir);
  EXPECT_EQ(back.keyframes.size(), map.keyframes.size());
  EXPECT_EQ(back.meta.created_ns, map.meta.created_ns);
  EXPECT_EQ(test::readFileBytes(dir / "trajectory.tum"), "1 0 0 0 0 0 0 1\n");
  EXPECT_EQ(test::readFileBytes(dir / "exports" / "mine.txt"), "not radarslam's\n");
  EXPECT_FALSE(fs::exists(mapTempDir(dir)));
  EXPECT_FALSE(fs::exists(mapBackupDir(dir)));
}

TEST(CliMapLayers, BadInputIsAOneLineError) {
  test::TempDir tmp;
  auto r = runCli("map-layers '" + (tmp / "nothing").string() + "'", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(oneLine(r.err).find("nothing"), std::string::npos) << r.err;

  fs::create_directories(tmp / "notamap");
  test::writeFileBytes(tmp / "notamap" / "file.txt", "x");
  r = runCli("map-layers '" + (tmp / "notamap").string() + "'", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(oneLine(r.err).find("manifest.yaml"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(tmp / "notamap" / "file.txt"));

  saveMap(ringMap(), tmp / "m");
  r = runCli("map-layers '" + (tmp / "m").string() + "' --resolution 0", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(oneLine(r.err).find("--resolution"), std::string::npos) << r.err;
  test::writeFileBytes(tmp / "bad.yaml", "map_layers:\n  grid_resolution_m: -1\n");
  r = runCli("map-layers '" + (tmp / "m").string() + "' --config '" + (tmp / "bad.yaml").string() + "'", tmp);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(oneLine(r.err).find("grid_resolution_m"), std::string::npos) << r.err;
  EXPECT_FALSE(readMapManifest(tmp / "m").layers.has_value());  // untouched

  r = runCli("map-layers --help", tmp);
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--resolution"), std::string::npos);
}

}  // namespace
}  // namespace radarslam
