// The map files layer without DDS (dds/map_file_publisher.h, dds/map_file_assembler.h): the chunks
// the server sends reassemble into a loadable copy of the map, and hostile or inconsistent chunks
// (path traversal, absolute paths, files the manifest does not list, wrong SHA-256, chunk count
// mismatches, duplicates, gaps) are one-line errors; chunks of an older publication are ignored,
// a newer publication starts over. Nothing is ever written outside the receiving directory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <radarslam/core/errors.h>
#include <radarslam/dds/map_file_assembler.h>
#include <radarslam/dds/map_file_publisher.h>
#include <radarslam/map/map_io.h>
#include <radarslam/map/sha256.h>

#include "dds_test_util.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using dds::MapFileChunkMsg;

constexpr StampNs kStamp = 1'700'000'000'000'000'000LL;

struct Fixture {
  test::TempDir tmp;
  fs::path map_dir = tmp.path() / "map";
  fs::path out = tmp.path() / "recv" / "inner";  // its parent shows writes that escape it
  Fixture(unsigned seed = 1) {
    saveMap(test::syntheticMap(5, 300, 30.0, seed), map_dir);
    fs::create_directories(out);
  }
  std::vector<MapFileChunkMsg> chunks(std::uint32_t revision, StampNs stamp = kStamp,
                                      std::size_t chunk_bytes = 4000) const {
    return chunksOf(map_dir, revision, stamp, chunk_bytes);
  }
  static std::vector<MapFileChunkMsg> chunksOf(const fs::path& dir, std::uint32_t revision, StampNs stamp,
                                               std::size_t chunk_bytes) {
    std::vector<MapFileChunkMsg> v;
    dds::MapFilesParams p;
    p.chunk_bytes = chunk_bytes;
    dds::forEachMapFileChunk(dir, {"map", revision, stamp, ""}, p, {},
                             [&](const MapFileChunkMsg& c) { v.push_back(c); });
    return v;
  }
  /// Feeds every chunk; returns the InputError text ("" if none) and whether it completed.
  std::pair<std::string, bool> feed(const std::vector<MapFileChunkMsg>& chunks) const {
    dds::MapFileAssembler a(out, "dds:");
    bool done = false;
    try {
      for (const auto& c : chunks) done = a.add(c);
    } catch (const InputError& e) {
      return {e.what(), done};
    }
    return {"", done};
  }
  /// Nothing but the receiving directory next to it.
  bool nothingEscaped() const {
    for (const auto& e : fs::directory_iterator(out.parent_path()))
      if (e.path() != out) return false;
    for (const auto& e : fs::recursive_directory_iterator(out))
      if (fs::is_symlink(e.symlink_status())) return false;
    return true;
  }
};

/// Index of the first chunk of `path` (and how many it has).
std::size_t firstOf(const std::vector<MapFileChunkMsg>& v, const std::string& path) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i].path == path) return i;
  ADD_FAILURE() << "no chunk of " << path;
  return 0;
}

TEST(MapFileAssembler, ReassemblesALoadableCopy) {
  Fixture f;
  const auto chunks = f.chunks(1);
  ASSERT_GT(chunks.size(), 6u);  // keyframes.bin takes several chunks of 4000 B
  EXPECT_EQ(chunks.front().path, "manifest.yaml");
  dds::MapFileAssembler a(f.out, "dds:");
  for (std::size_t i = 0; i < chunks.size(); ++i) EXPECT_EQ(a.add(chunks[i]), i + 1 == chunks.size()) << i;
  EXPECT_EQ(a.filesComplete(), 5u);
  EXPECT_EQ(a.revision(), 1u);
  for (const char* name : {"manifest.yaml", "parameters.yaml", "keyframes.bin", "points.bin", "graph.bin"})
    EXPECT_EQ(test::readText(f.out / name), test::readText(f.map_dir / name)) << name;
  EXPECT_FALSE(fs::exists(f.out / "layers"));  // not sent by default: loadMap does not read them
  const KeyframeMap a_map = loadMap(f.out), b_map = loadMap(f.map_dir);
  ASSERT_EQ(a_map.keyframes.size(), b_map.keyframes.size());
  EXPECT_TRUE(f.nothingEscaped());
}

TEST(MapFileAssembler, RejectsPathsLeavingTheDirectory) {
  for (const std::string bad : {"../x", "../../etc/passwd", "/tmp/x", "a/../../x", "./keyframes.bin", "a//b",
                                "layers/a/b", "", "key frames.bin", "x\\..\\y", ".."}) {
    Fixture f;
    auto chunks = f.chunks(1);
    const std::size_t i = firstOf(chunks, "keyframes.bin");
    for (std::size_t j = i; j < chunks.size() && chunks[j].file_index == chunks[i].file_index; ++j)
      chunks[j].path = bad;
    const auto [error, done] = f.feed(chunks);
    EXPECT_FALSE(done) << bad;
    EXPECT_NE(error.find("dds:: "), std::string::npos) << bad << ": " << error;
    EXPECT_NE(error.find("path"), std::string::npos) << bad << ": " << error;
    EXPECT_TRUE(f.nothingEscaped()) << bad;
  }
}

TEST(MapFileAssembler, RejectsFilesTheManifestDoesNotList) {
  Fixture f;
  auto chunks = f.chunks(1);
  for (auto& c : chunks)
    if (c.path == "graph.bin") c.path = "graph2.bin";
  const auto [error, done] = f.feed(chunks);
  EXPECT_FALSE(done);
  EXPECT_NE(error.find("graph2.bin: not a file the manifest lists"), std::string::npos) << error;
}

TEST(MapFileAssembler, RejectsAPublicationWithoutAFileTheMapNeeds) {
  Fixture f;
  auto chunks = f.chunks(1);
  ASSERT_EQ(chunks.back().path, "graph.bin");  // the last file: the others keep their indices
  std::vector<MapFileChunkMsg> without;
  for (const auto& c : chunks)
    if (c.path != "graph.bin") without.push_back(c);
  for (auto& c : without) {
    c.file_count -= 1;
    c.total_chunks = static_cast<std::uint32_t>(without.size());
  }
  const auto [error, done] = f.feed(without);
  EXPECT_FALSE(done);
  EXPECT_NE(error.find("graph.bin: listed by the manifest but not in the publication"), std::string::npos)
      << error;
}

TEST(MapFileAssembler, RejectsAWrongChecksum) {
  Fixture f;
  auto chunks = f.chunks(1);
  chunks[firstOf(chunks, "keyframes.bin") + 1].data[100] ^= 0x01;
  const auto [error, done] = f.feed(chunks);
  EXPECT_FALSE(done);
  EXPECT_NE(error.find("keyframes.bin: SHA-256 mismatch"), std::string::npos) << error;
}

// A publisher stating huge files must not make the receiver write without bound: the stated sizes
// are summed as files appear and checked against the limit before anything of that file is written.
TEST(MapFileAssembler, RefusesAPublicationLargerThanTheLimit) {
  Fixture f;
  const auto chunks = f.chunks(1);
  std::uint64_t total = 0;
  for (const auto& c : chunks)
    if (c.chunk_index == 0) total += c.file_size;
  {
    dds::MapFileAssembler exact(f.out, "dds:", total);
    bool done = false;
    for (const auto& c : chunks) done = exact.add(c);
    EXPECT_TRUE(done);
  }
  for (const auto& e : fs::directory_iterator(f.out)) fs::remove_all(e.path());
  dds::MapFileAssembler a(f.out, "dds:", total - 1);
  std::string error;
  try {
    for (const auto& c : chunks) a.add(c);
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("exceed the limit"), std::string::npos) << error;
  EXPECT_FALSE(a.complete());
  // A stated 2^60-byte file is refused outright.
  auto huge = f.chunks(1);
  huge[firstOf(huge, "keyframes.bin")].file_size = std::uint64_t{1} << 60;
  huge[firstOf(huge, "keyframes.bin")].chunk_count = 1u << 20;
  const auto [huge_error, done] = f.feed(huge);
  EXPECT_FALSE(done);
  EXPECT_FALSE(huge_error.empty());
  EXPECT_TRUE(f.nothingEscaped());
}

TEST(MapFileAssembler, RejectsAFileThatDiffersFromTheManifest) {
  // Self-consistent chunks (SHA-256 of what is sent) of a file the manifest describes otherwise.
  Fixture f;
  auto chunks = f.chunks(1);
  const std::size_t i = firstOf(chunks, "parameters.yaml");
  ASSERT_EQ(chunks[i].chunk_count, 1u);
  chunks[i].data.push_back('#');
  chunks[i].file_size += 1;
  chunks[i].file_sha256 = sha256Hex(std::string(chunks[i].data.begin(), chunks[i].data.end()));
  const auto [error, done] = f.feed(chunks);
  EXPECT_FALSE(done);
  EXPECT_NE(error.find("parameters.yaml: size or SHA-256 differs from the manifest's"), std::string::npos)
      << error;
}

TEST(MapFileAssembler, RejectsChunkCountMismatches) {
  {
    Fixture f;
    auto chunks = f.chunks(1);
    chunks[firstOf(chunks, "keyframes.bin") + 1].chunk_count += 1;
    const auto [error, done] = f.feed(chunks);
    EXPECT_NE(error.find("keyframes.bin: chunk count mismatch"), std::string::npos) << error;
  }
  {
    Fixture f;  // a file larger than its chunks can hold (e.g. to make the receiver hash a huge sparse file)
    auto chunks = f.chunks(1);
    const std::size_t i = firstOf(chunks, "keyframes.bin");
    for (std::size_t j = i; j < chunks.size() && chunks[j].path == "keyframes.bin"; ++j)
      chunks[j].file_size = std::uint64_t{1} << 50;
    const auto [error, done] = f.feed(chunks);
    EXPECT_NE(error.find("keyframes.bin: 1125899906842624 bytes cannot be"), std::string::npos) << error;
  }
  {
    Fixture f;  // a publication whose total does not add up
    auto chunks = f.chunks(1);
    for (auto& c : chunks) c.total_chunks += 1;
    const auto [error, done] = f.feed(chunks);
    EXPECT_FALSE(done);
    EXPECT_NE(error.find("chunks make all files, the publication says"), std::string::npos) << error;
  }
  {
    Fixture f;  // one chunk disagrees with the others about the publication
    auto chunks = f.chunks(1);
    chunks[3].total_chunks += 1;
    const auto [error, done] = f.feed(chunks);
    EXPECT_NE(error.find("disagrees with the publication"), std::string::npos) << error;
  }
  {
    Fixture f;  // a file's last chunk missing, replaced by a chunk that leaves a gap
    auto chunks = f.chunks(1);
    const std::size_t i = firstOf(chunks, "keyframes.bin");
    chunks[i + 1].offset += 1;
    const auto [error, done] = f.feed(chunks);
    EXPECT_FALSE(done);
    EXPECT_NE(error.find("overlap or leave a gap"), std::string::npos) << error;
  }
}

TEST(MapFileAssembler, RejectsDuplicateChunks) {
  Fixture f;
  auto chunks = f.chunks(1);
  const std::size_t i = firstOf(chunks, "keyframes.bin");
  chunks.insert(chunks.begin() + static_cast<std::ptrdiff_t>(i + 1), chunks[i]);
  const auto [error, done] = f.feed(chunks);
  EXPECT_FALSE(done);
  EXPECT_NE(error.find("keyframes.bin: duplicate chunk 0"), std::string::npos) << error;
}

TEST(MapFileAssembler, IgnoresOlderPublicationsAndRestartsOnANewerOne) {
  Fixture f(1);
  const auto old_chunks = f.chunks(1);  // revision 1: the map of seed 1
  Fixture g(2);
  const auto new_chunks = g.chunks(2, kStamp + 1);  // revision 2: another map
  // Half of revision 1, then revision 2 with revision 1's chunks mixed in.
  dds::MapFileAssembler a(f.out, "dds:");
  for (std::size_t i = 0; i < old_chunks.size() / 2; ++i) EXPECT_FALSE(a.add(old_chunks[i]));
  bool done = false;
  for (std::size_t i = 0; i < new_chunks.size(); ++i) {
    done = a.add(new_chunks[i]);
    if (i < old_chunks.size()) {
      EXPECT_EQ(a.add(old_chunks[i]), done);  // ignored
    }
  }
  EXPECT_TRUE(done);
  EXPECT_EQ(a.revision(), 2u);
  EXPECT_GT(a.chunksIgnored(), 0u);
  for (const char* name : {"manifest.yaml", "keyframes.bin", "graph.bin"})
    EXPECT_EQ(test::readText(f.out / name), test::readText(g.map_dir / name)) << name;
  // The same revision from a restarted server (newer stamp) also starts over.
  const auto restarted = f.chunks(2, kStamp + 2);
  for (const auto& c : restarted) done = a.add(c);
  EXPECT_TRUE(done);
  EXPECT_EQ(test::readText(f.out / "keyframes.bin"), test::readText(f.map_dir / "keyframes.bin"));
  EXPECT_TRUE(f.nothingEscaped());
}

TEST(MapFileAssembler, ServerSideChecksTheFilesAgainstTheManifest) {
  Fixture f;
  {  // same size, one byte changed: nothing is produced
    std::string bytes = test::readText(f.map_dir / "graph.bin");
    bytes[30] ^= 0x10;
    std::ofstream(f.map_dir / "graph.bin", std::ios::binary | std::ios::trunc) << bytes;
  }
  bool started = false;
  try {
    Fixture::chunksOf(f.map_dir, 1, kStamp, 4000);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("graph.bin: checksum mismatch"), std::string::npos) << e.what();
  }
  dds::MapFilesParams p;
  EXPECT_THROW(dds::forEachMapFileChunk(f.map_dir, {"map", 1, kStamp, ""}, p,
                                        [&](const dds::MapFilesSummary&) { started = true; }, {}),
               InputError);
  EXPECT_FALSE(started);
}

TEST(MapFileAssembler, WithLayersCarriesTheLayerFiles) {
  test::TempDir tmp;
  const fs::path map_dir = tmp / "map", out = tmp / "out";
  saveMap(test::syntheticMap(3, 200, 20.0, 3), map_dir, {}, MapLayerParams{});
  fs::create_directories(out);
  dds::MapFilesParams p;
  p.with_layers = true;
  std::vector<MapFileChunkMsg> v;
  dds::forEachMapFileChunk(map_dir, {"map", 1, kStamp, ""}, p, {},
                           [&](const MapFileChunkMsg& c) { v.push_back(c); });
  dds::MapFileAssembler a(out, "dds:");
  bool done = false;
  for (const auto& c : v) done = a.add(c);
  EXPECT_TRUE(done);
  EXPECT_EQ(a.filesComplete(), 9u);
  EXPECT_EQ(test::readText(out / "layers/map.bt"), test::readText(map_dir / "layers/map.bt"));
}

}  // namespace
}  // namespace radarslam
