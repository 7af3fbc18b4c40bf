// Fuzz target: the map files layer (radarslam/MapFileChunk, docs/dds.md) through MapFileAssembler,
// as `radarslam localize dds: DIR` reassembles a served map. The bytes are decoded into up to 16
// chunks (what Cyclone DDS hands over after deserialising any sample a publisher sends):
//   per chunk: u8 flags, u8 path length, path, u8 revision, u8 file_count, u8 total_chunks,
//   u8 file_index, u8 chunk_index, u8 chunk_count, u16 offset, u16 file_size, u16 data length, data.
// flags bit 0: file_sha256 = SHA-256 of the chunk's data (a whole file sent honestly), else 64
// hex digits taken from the input; bit 1: a malformed manifest SHA-256; bit 2: another map name.
// Invariants: only InputError escapes; nothing is created outside the assembler's directory, and
// inside it only paths mapFilePathProblem accepts, within the size limit; `add` returns true only
// when the assembler says complete.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "fuzz_common.h"
#include "radarslam/dds/map_file_assembler.h"
#include "radarslam/map/sha256.h"

namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kMaxBytes = 100 * 1024;  // below what 16 chunks can state: the limit is reached

std::string hex64(radarslam::fuzz::ByteReader& in) {
  static const char* digits = "0123456789abcdef";
  std::string out(64, '0');
  for (char& c : out) c = digits[in.get<std::uint8_t>() & 15];
  return out;
}

/// Every entry under `root` is inside `dir`, a regular file or directory with an accepted path.
void checkTree(const fs::path& root, const fs::path& dir) {
  std::uint64_t bytes = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const fs::path rel = e.path().lexically_relative(dir);
    if (rel.empty() || *rel.begin() == "..") std::abort();  // outside the assembler's directory
    if (e.is_symlink()) std::abort();
    if (e.is_directory()) continue;
    if (!e.is_regular_file()) std::abort();
    if (!radarslam::dds::mapFilePathProblem(rel.generic_string()).empty()) std::abort();
    bytes += e.file_size();
  }
  if (bytes > kMaxBytes) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radarslam;
  const fs::path root = fuzz::scratchDir() / "chunks";
  const fs::path dir = root / "map";
  fs::remove_all(root);
  fs::create_directories(dir);
  fuzz::ByteReader in(data, size);
  dds::MapFileAssembler assembler(dir, "dds:fuzz", kMaxBytes);
  const std::string manifest_sha(64, 'a');
  try {
    for (int k = 0; k < 16 && !in.empty(); ++k) {
      dds::MapFileChunkMsg c;
      const auto flags = in.get<std::uint8_t>();
      c.header.stamp.sec = 1;
      c.header.frame_id = "map";
      c.map_name = (flags & 4) ? "other" : "demo";
      c.manifest_sha256 = (flags & 2) ? "not-hex" : manifest_sha;
      c.path = in.text(in.get<std::uint8_t>());
      c.revision = in.get<std::uint8_t>();
      c.file_count = in.get<std::uint8_t>();
      c.total_chunks = in.get<std::uint8_t>();
      c.file_index = in.get<std::uint8_t>();
      c.chunk_index = in.get<std::uint8_t>();
      c.chunk_count = in.get<std::uint8_t>();
      c.offset = in.get<std::uint16_t>();
      c.file_size = in.get<std::uint16_t>();
      const std::string bytes = in.text(in.get<std::uint16_t>());
      c.data.assign(bytes.begin(), bytes.end());
      c.file_sha256 = (flags & 1) ? sha256Hex(bytes) : hex64(in);
      const bool done = assembler.add(c);
      if (done && !assembler.complete()) std::abort();
    }
  } catch (const InputError&) {
    // the expected answer to a hostile chunk
  }
  checkTree(root, dir);
  return 0;
}
