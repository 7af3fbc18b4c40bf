// loadMap checks the content of a map, not only its checksums: a map whose files were rewritten
// with valid checksums (here: a corrupted struct saved by saveMap, or bytes patched and the
// manifest's SHA-256 rewritten) must fail with one line naming the file and the problem.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
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

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// loadMap(dir) must throw one line containing `file` and `problem`.
void expectLoadError(const fs::path& dir, const std::string& file, const std::string& problem) {
  try {
    loadMap(dir);
    ADD_FAILURE() << "loadMap accepted a map with " << problem;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(e.where().find(file), std::string::npos) << msg;
    EXPECT_NE(e.problem().find(problem), std::string::npos) << "'" << problem << "' not in: " << msg;
  }
}

// Saves the synthetic map after `corrupt` (saveMap writes valid checksums) and expects the error.
void expectCorruptionRejected(const std::function<void(KeyframeMap&)>& corrupt, const std::string& file,
                              const std::string& problem) {
  radarslam::test::TempDir tmp;
  KeyframeMap map = radarslam::test::syntheticMap(4, 20);
  corrupt(map);
  saveMap(map, tmp / "m");
  expectLoadError(tmp / "m", file, problem);
}

// Rewrites `bytes:` and `sha256:` of `file` in the manifest to match its current content.
void rewriteChecksum(const fs::path& dir, const std::string& file) {
  const std::string bytes = readFileBytes(dir / file);
  std::string m = readFileBytes(dir / "manifest.yaml");
  const auto at = m.find("name: \"" + file + "\"");
  ASSERT_NE(at, std::string::npos);
  const auto b = m.find("bytes: ", at) + 7;
  m.replace(b, m.find('\n', b) - b, std::to_string(bytes.size()));
  const auto s = m.find("sha256: \"", at) + 9;
  m.replace(s, 64, radarslam::sha256Hex(bytes));
  writeFileBytes(dir / "manifest.yaml", m);
}

}  // namespace

TEST(MapValidation, TheValidSyntheticMapLoads) {
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(4, 20), tmp / "m");
  EXPECT_EQ(loadMap(tmp / "m").keyframes.size(), 4u);
}

TEST(MapValidation, NonFiniteOrHugePosesAreRejected) {
  expectCorruptionRejected([](KeyframeMap& m) { m.keyframes[2].pose.x = kNaN; }, "keyframes.bin",
                           "keyframe 12: pose x is NaN");
  expectCorruptionRejected([](KeyframeMap& m) { m.keyframes[0].pose.y = -kInf; }, "keyframes.bin",
                           "keyframe 10: pose y is -inf");
  expectCorruptionRejected([](KeyframeMap& m) { m.keyframes[1].pose.x = 1e300; }, "keyframes.bin",
                           "pose x is 1.0000000000000001e+300, beyond +-10000000");
  expectCorruptionRejected([](KeyframeMap& m) { m.keyframes[3].pose.phi = kNaN; }, "keyframes.bin",
                           "keyframe 13: pose phi is NaN");
  expectCorruptionRejected([](KeyframeMap& m) { m.keyframes[3].points[5].x = static_cast<float>(kNaN); },
                           "keyframes.bin", "keyframe 13: point 5 x is NaN");
  expectCorruptionRejected([](KeyframeMap& m) { m.keyframes[0].descriptor[3] = static_cast<float>(kInf); },
                           "keyframes.bin", "descriptor value 3 is inf");
}

TEST(MapValidation, DuplicateAndDanglingIdsAreRejected) {
  expectCorruptionRejected([](KeyframeMap& m) { m.keyframes[3].id = m.keyframes[1].id; }, "keyframes.bin",
                           "keyframe 11: duplicate keyframe id");
  expectCorruptionRejected([](KeyframeMap& m) { m.edges[1].to = 99; }, "graph.bin",
                           "references keyframe 99, which does not exist");
  expectCorruptionRejected([](KeyframeMap& m) { m.edges[0].to = m.edges[0].from; }, "graph.bin",
                           "connects a keyframe to itself");
  expectCorruptionRejected([](KeyframeMap& m) { m.points[4].observed_by.push_back(7); }, "points.bin",
                           "map point 1004: observed by keyframe 7, which does not exist");
  expectCorruptionRejected([](KeyframeMap& m) { m.points[6].id = m.points[2].id; }, "points.bin",
                           "duplicate map point id");
  expectCorruptionRejected([](KeyframeMap& m) { m.points[3].y = kNaN; }, "points.bin",
                           "map point 1003: y is NaN");
}

TEST(MapValidation, BadEdgesAreRejected) {
  expectCorruptionRejected([](KeyframeMap& m) { m.edges[2].relative.x = kNaN; }, "graph.bin",
                           "relative pose x is NaN");
  expectCorruptionRejected([](KeyframeMap& m) { m.edges[2].information[4] = kNaN; }, "graph.bin",
                           "information matrix entry 4 is NaN");
  expectCorruptionRejected([](KeyframeMap& m) { m.edges[1].information[1] = 30; }, "graph.bin",
                           "information matrix is not symmetric");
  expectCorruptionRejected([](KeyframeMap& m) { m.edges[0].information[8] = -5; }, "graph.bin",
                           "not positive semi-definite");
}

TEST(MapValidation, ImplausibleSensorGeometryIsRejected) {
  expectCorruptionRejected([](KeyframeMap& m) { m.meta.sensor.range_resolution_m = 0; }, "manifest.yaml",
                           "sensor.range_resolution_m must be > 0");
  expectCorruptionRejected([](KeyframeMap& m) { m.meta.sensor.range_resolution_m = -0.04; }, "manifest.yaml",
                           "sensor.range_resolution_m must be > 0");
  expectCorruptionRejected([](KeyframeMap& m) { m.meta.sensor.range_resolution_m = kNaN; }, "manifest.yaml",
                           "range_resolution_m");
  expectCorruptionRejected([](KeyframeMap& m) { m.meta.sensor.num_azimuths = 0; }, "manifest.yaml",
                           "sensor.num_azimuths must be 1..16384 (got 0)");
  expectCorruptionRejected([](KeyframeMap& m) { m.meta.sensor.num_bins = 0; }, "manifest.yaml",
                           "sensor.num_bins must be 1..65536");
  expectCorruptionRejected([](KeyframeMap& m) { m.meta.sensor.range_offset_m = 1e300; }, "manifest.yaml",
                           "range_offset_m is 1.0000000000000001e+300");
  // A negative count in the manifest text (the manifest has no checksum of its own).
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(2, 10), tmp / "m");
  std::string m = readFileBytes(tmp / "m" / "manifest.yaml");
  m.replace(m.find("num_azimuths: 400"), 17, "num_azimuths: -400");
  writeFileBytes(tmp / "m" / "manifest.yaml", m);
  expectLoadError(tmp / "m", "manifest.yaml", "num_azimuths");
}

TEST(MapValidation, PatchedBytesWithRewrittenChecksumsAreRejected) {
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(4, 20), tmp / "m");
  // keyframes.bin: 24-byte header, then id (u64), stamp (i64), pose x (f64) of the first keyframe.
  std::string kf = readFileBytes(tmp / "m" / "keyframes.bin");
  const double nan = kNaN;
  kf.replace(24 + 16, 8, reinterpret_cast<const char*>(&nan), 8);
  writeFileBytes(tmp / "m" / "keyframes.bin", kf);
  rewriteChecksum(tmp / "m", "keyframes.bin");
  expectLoadError(tmp / "m", "keyframes.bin", "keyframe 10: pose x is NaN");
}

TEST(MapValidation, ManifestStringsRoundTripWhateverBytesTheyHold) {
  radarslam::test::TempDir tmp;
  KeyframeMap map = radarslam::test::syntheticMap(2, 10);
  const std::string hostile[] = {
      std::string("/data/\xff\xfe-not-utf8/\"quoted\" path\nline2 #: comment\t\x01\x7f end"),
      std::string("caf\xc3\xa9 \xf0\x9f\x98\x80 back\\slash 'single' {brace} [x]: y"),
      std::string(" leading and trailing space \n"),
      std::string("nul\0inside", 10),
      std::string(),
  };
  for (const auto& s : hostile) {
    map.meta.source_dataset = s;
    map.meta.software_version = s + "v";
    saveMap(map, tmp / "m");
    const std::string manifest = readFileBytes(tmp / "m" / "manifest.yaml");
    for (unsigned char c : manifest) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f)) << int(c);
    const KeyframeMap back = loadMap(tmp / "m");
    EXPECT_EQ(back.meta.source_dataset, s);
    EXPECT_EQ(back.meta.software_version, s + "v");
    EXPECT_EQ(back.meta, map.meta);
  }
}

TEST(MapValidation, ABrokenHexTwinIsAnError) {
  radarslam::test::TempDir tmp;
  KeyframeMap map = radarslam::test::syntheticMap(2, 10);
  map.meta.source_dataset = "\xff";
  saveMap(map, tmp / "m");
  std::string m = readFileBytes(tmp / "m" / "manifest.yaml");
  const std::string twin = "source_dataset_hex: \"ff\"";
  const auto at = m.find(twin);
  ASSERT_NE(at, std::string::npos) << m;
  m.replace(at, twin.size(), "source_dataset_hex: \"f\"");
  writeFileBytes(tmp / "m" / "manifest.yaml", m);
  expectLoadError(tmp / "m", "manifest.yaml", "source_dataset_hex");
}

TEST(MapValidation, WhetherTheCloudsAreMotionCompensatedRoundTrips) {
  radarslam::test::TempDir tmp;
  KeyframeMap map = radarslam::test::syntheticMap(2, 10);
  for (const bool compensated : {false, true}) {
    map.meta.clouds_motion_compensated = compensated;
    saveMap(map, tmp / "m");
    EXPECT_EQ(loadMap(tmp / "m").meta.clouds_motion_compensated, compensated);
  }
  // A manifest without the key (written before it existed, by radarslam map): compensated.
  std::string m = readFileBytes(tmp / "m" / "manifest.yaml");
  const std::string line = "clouds_motion_compensated: true\n";
  const auto at = m.find(line);
  ASSERT_NE(at, std::string::npos) << m;
  writeFileBytes(tmp / "m" / "manifest.yaml", std::string(m).erase(at, line.size()));
  EXPECT_TRUE(loadMap(tmp / "m").meta.clouds_motion_compensated);
  writeFileBytes(tmp / "m" / "manifest.yaml",
                 std::string(m).replace(at, line.size(), "clouds_motion_compensated: maybe\n"));
  expectLoadError(tmp / "m", "manifest.yaml", "clouds_motion_compensated");
}

TEST(MapValidation, AFifoOrADirectoryInPlaceOfAMapFileIsRefused) {
  radarslam::test::TempDir tmp;
  saveMap(radarslam::test::syntheticMap(2, 10), tmp / "m");
  fs::remove(tmp / "m" / "graph.bin");
  fs::create_directory(tmp / "m" / "graph.bin");
  expectLoadError(tmp / "m", "graph.bin", "not a regular file (a directory)");
  fs::remove(tmp / "m" / "keyframes.bin");
  ASSERT_EQ(::mkfifo((tmp / "m" / "keyframes.bin").c_str(), 0600), 0);
  expectLoadError(tmp / "m", "keyframes.bin", "not a regular file (a FIFO)");  // and no hang in open()
  fs::remove(tmp / "m" / "manifest.yaml");
  ASSERT_EQ(::mkfifo((tmp / "m" / "manifest.yaml").c_str(), 0600), 0);
  expectLoadError(tmp / "m", "manifest.yaml", "not a regular file (a FIFO)");
}
