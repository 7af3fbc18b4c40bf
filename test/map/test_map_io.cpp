// Map directory save/load: round trip, checksum/truncation/version errors naming the file, and
// crash safety of the atomic directory swap.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "file_contents.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"
#include "synthetic_map.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using radarslam::InputError;
using radarslam::KeyframeMap;
using radarslam::loadMap;
using radarslam::saveMap;

namespace {

using radarslam::test::readFileBytes;
using radarslam::test::writeFileBytes;

// Runs loadMap(dir) expecting an InputError whose message contains each of `parts`.
void expectLoadError(const fs::path& dir, std::initializer_list<std::string> parts) {
  try {
    loadMap(dir);
    ADD_FAILURE() << "loadMap succeeded on a broken map";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
}

}  // namespace

TEST(MapIo, ANewMapIsOfTheCurrentFormat) {
  // (A static_assert here is not a constant expression for clang 14: MapMetadata holds strings.)
  EXPECT_EQ(radarslam::MapMetadata{}.format_version, radarslam::kMapFormatVersion);
}

TEST(MapIo, RoundTripIsExact) {
  radarslam::test::TempDir tmp;
  const KeyframeMap map = radarslam::test::syntheticMap();
  saveMap(map, tmp / "m");
  for (const char* f : {"manifest.yaml", "parameters.yaml", "keyframes.bin", "points.bin", "graph.bin"})
    EXPECT_TRUE(fs::is_regular_file(tmp / "m" / f)) << f;
  const KeyframeMap back = loadMap(tmp / "m");
  EXPECT_EQ(back.meta, map.meta);
  ASSERT_EQ(back.keyframes.size(), map.keyframes.size());
  for (std::size_t i = 0; i < map.keyframes.size(); ++i)
    EXPECT_TRUE(back.keyframes[i] == map.keyframes[i]) << i;
  EXPECT_EQ(back.points, map.points);
  EXPECT_EQ(back.edges, map.edges);
  EXPECT_EQ(back.edges.back().kind, radarslam::EdgeKind::Loop);
  EXPECT_TRUE(back == map);
  // The keyframe file has exactly the documented size (maps/README.md).
  std::size_t expected = 24;
  for (const auto& kf : map.keyframes) expected += 48 + 12 * kf.points.size() + 4 * kf.descriptor.size();
  EXPECT_EQ(fs::file_size(tmp / "m" / "keyframes.bin"), expected);
}

TEST(MapIo, TrailingSlashIsTheSameMap) {
  radarslam::test::TempDir tmp;
  const KeyframeMap a = radarslam::test::syntheticMap(2, 10), b = radarslam::test::syntheticMap(3, 10);
  saveMap(a, tmp.path() / "m" / "");
  EXPECT_TRUE(loadMap(tmp / "m") == a);
  saveMap(b, tmp.path() / "m" / "");
  EXPECT_TRUE(loadMap(tmp.path() / "m" / "") == b);
  EXPECT_EQ(radarslam::mapTempDir(tmp.path() / "m" / ""), tmp / ".m.map-tmp");
  for (const auto& e : fs::directory_iterator(tmp.path())) EXPECT_EQ(e.path().filename(), "m");
}

TEST(MapIo, EmptyMapRoundTrips) {
  radarslam::test::TempDir tmp;
  KeyframeMap map;
  map.meta.created_ns = 42;
  saveMap(map, tmp / "empty");
  EXPECT_TRUE(loadMap(tmp / "empty") == map);
}

TEST(MapIo, SaveFillsCreationTime) {
  radarslam::test::TempDir tmp;
  KeyframeMap map = radarslam::test::syntheticMap(2, 10);
  map.meta.created_ns = 0;
  saveMap(map, tmp / "m");
  const auto back = loadMap(tmp / "m");
  EXPECT_GT(back.meta.created_ns, 1'600'000'000'000'000'000LL);  // after 2020
  EXPECT_NE(readFileBytes(tmp / "m" / "manifest.yaml").find("created_utc: \"20"), std::string::npos);
}

TEST(MapIo, CorruptByteIsAChecksumError) {
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(), tmp / "m");
  for (const char* file : {"keyframes.bin", "points.bin", "graph.bin", "parameters.yaml"}) {
    const fs::path p = tmp / "m" / file;
    const std::string good = readFileBytes(p);
    std::string bad = good;
    bad[bad.size() / 2] ^= 0x01;
    writeFileBytes(p, bad);
    expectLoadError(tmp / "m", {file, "checksum mismatch"});
    writeFileBytes(p, good);
  }
  EXPECT_NO_THROW(loadMap(tmp / "m"));
}

TEST(MapIo, TruncatedFileIsAnError) {
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(), tmp / "m");
  const fs::path p = tmp / "m" / "keyframes.bin";
  const std::string good = readFileBytes(p);
  writeFileBytes(p, good.substr(0, good.size() - 100));
  expectLoadError(tmp / "m", {"keyframes.bin", "truncated"});
  writeFileBytes(p, good);
  fs::remove(tmp / "m" / "graph.bin");
  expectLoadError(tmp / "m", {"graph.bin", "missing"});
}

TEST(MapIo, NewerFormatVersionIsRejected) {
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(2, 10), tmp / "m");
  const fs::path manifest = tmp / "m" / "manifest.yaml";
  std::string text = readFileBytes(manifest);
  const std::string current = "format_version: " + std::to_string(radarslam::kMapFormatVersion) + "\n";
  const auto pos = text.find(current);
  ASSERT_NE(pos, std::string::npos);
  const std::string newer = std::to_string(radarslam::kMapFormatVersion + 1);
  text.replace(pos, current.size(), "format_version: " + newer + "\n");
  writeFileBytes(manifest, text);
  expectLoadError(tmp / "m", {"manifest.yaml", "version " + newer + " is newer"});
}

// A .bin file of a newer version is refused even when its checksum is consistent (manifest fixed).
TEST(MapIo, NewerBinaryFileVersionIsRejected) {
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(2, 10), tmp / "m");
  const fs::path kf = tmp / "m" / "keyframes.bin";
  const std::string old_bytes = readFileBytes(kf);
  std::string bytes = old_bytes;
  ASSERT_EQ(bytes.substr(0, 8), "RSLMKEYF");
  bytes[8] = static_cast<char>(radarslam::kMapFormatVersion + 1);  // u32 version, little-endian, offset 8
  writeFileBytes(kf, bytes);
  const fs::path manifest = tmp / "m" / "manifest.yaml";
  std::string text = readFileBytes(manifest);
  const std::string old_sha = radarslam::sha256Hex(old_bytes);
  const auto pos = text.find(old_sha);
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, old_sha.size(), radarslam::sha256Hex(bytes));
  writeFileBytes(manifest, text);
  expectLoadError(
      tmp / "m",
      {"keyframes.bin", "format version " + std::to_string(radarslam::kMapFormatVersion + 1) + " is newer"});
}

TEST(MapIo, NotAMapDirectory) {
  radarslam::test::TempDir tmp;
  expectLoadError(tmp / "nothing", {"nothing", "does not exist"});
  fs::create_directories(tmp / "plain");
  expectLoadError(tmp / "plain", {"manifest.yaml", "missing"});
}

TEST(MapIo, WriterCrashLeavesThePreviousMap) {
  radarslam::test::TempDir tmp;
  const KeyframeMap old_map = radarslam::test::syntheticMap(3, 20);
  saveMap(old_map, tmp / "m");
  const KeyframeMap new_map = radarslam::test::syntheticMap(5, 30);
  for (const char* crash_at : {"keyframes.bin", "graph.bin", "manifest.yaml"}) {
    radarslam::MapSaveHooks hooks;
    hooks.after_file = [&](const std::string& f) {
      if (f == crash_at) throw std::runtime_error("simulated crash");
    };
    EXPECT_THROW(saveMap(new_map, tmp / "m", hooks), std::runtime_error);
    EXPECT_TRUE(loadMap(tmp / "m") == old_map) << crash_at;
  }
  saveMap(new_map, tmp / "m");
  EXPECT_TRUE(loadMap(tmp / "m") == new_map);
  EXPECT_FALSE(fs::exists(radarslam::mapTempDir(tmp / "m")));
  EXPECT_FALSE(fs::exists(radarslam::mapBackupDir(tmp / "m")));
}

TEST(MapIo, StaleTempAndBackupDirectories) {
  radarslam::test::TempDir tmp;
  const fs::path dir = tmp / "m";
  const KeyframeMap a = radarslam::test::syntheticMap(3, 20), b = radarslam::test::syntheticMap(4, 25);
  saveMap(a, dir);
  // A crash while writing the temporary: a half-written temp dir next to the complete old map.
  fs::create_directories(radarslam::mapTempDir(dir));
  writeFileBytes(radarslam::mapTempDir(dir) / "keyframes.bin", "garbage");
  EXPECT_TRUE(loadMap(dir) == a);
  // A crash between "old -> backup" and "new -> place": only the backup is complete.
  fs::rename(dir, radarslam::mapBackupDir(dir));
  EXPECT_TRUE(loadMap(dir) == a);  // recovered
  EXPECT_TRUE(fs::exists(dir / "manifest.yaml"));
  EXPECT_FALSE(fs::exists(radarslam::mapBackupDir(dir)));
  // A crash after the new map was in place but before the backup was deleted.
  fs::create_directories(radarslam::mapBackupDir(dir));
  writeFileBytes(radarslam::mapBackupDir(dir) / "manifest.yaml", "format_version: 1\n");
  EXPECT_TRUE(loadMap(dir) == a);
  // The next save cleans both up.
  saveMap(b, dir);
  EXPECT_TRUE(loadMap(dir) == b);
  EXPECT_FALSE(fs::exists(radarslam::mapTempDir(dir)));
  EXPECT_FALSE(fs::exists(radarslam::mapBackupDir(dir)));
}

TEST(MapIo, ResolveMapPath) {
  radarslam::test::TempDir tmp;
  const fs::path cwd = fs::current_path();
  fs::current_path(tmp.path());
  ::unsetenv("RADARSLAM_MAPS_DIR");
  EXPECT_EQ(radarslam::resolveMapPath("campus"), fs::path("maps/campus"));
  EXPECT_EQ(radarslam::resolveMapPath("./campus"), fs::path("./campus"));
  EXPECT_EQ(radarslam::resolveMapPath("/abs/x"), fs::path("/abs/x"));
  ::setenv("RADARSLAM_MAPS_DIR", (tmp / "store").c_str(), 1);
  EXPECT_EQ(radarslam::resolveMapPath("campus"), tmp / "store" / "campus");
  fs::create_directories("maps/campus");  // a local map wins
  EXPECT_EQ(radarslam::resolveMapPath("campus"), fs::path("maps/campus"));
  ::unsetenv("RADARSLAM_MAPS_DIR");
  fs::current_path(cwd);
  EXPECT_THROW(radarslam::resolveMapPath(""), InputError);
}
