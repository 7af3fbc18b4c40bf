#pragma once
// Turns a freshly saved map directory into one as radarslam saved it before the layers (map
// format version 1): version 1 in the manifest and the binary file headers, checksums updated,
// no `layers:` section and no layers/ directory. For the tests of the fallbacks and map-layers.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "file_contents.h"
#include "radarslam/map/sha256.h"

namespace radarslam::test {

inline void downgradeToFormat1(const std::filesystem::path& dir) {
  std::string manifest = readFileBytes(dir / "manifest.yaml");
  for (const char* name : {"keyframes.bin", "points.bin", "graph.bin"}) {
    std::string bytes = readFileBytes(dir / name);
    const std::string old_sha = sha256Hex(bytes);
    const std::uint32_t one = 1;
    std::memcpy(bytes.data() + 8, &one, 4);  // header: 8-byte magic, u32 version (little-endian)
    writeFileBytes(dir / name, bytes);
    const auto pos = manifest.find(old_sha);
    if (pos == std::string::npos) throw std::runtime_error("downgradeToFormat1: checksum not in manifest");
    manifest.replace(pos, old_sha.size(), sha256Hex(bytes));
  }
  const auto v = manifest.find("format_version: 2\n");
  if (v == std::string::npos) throw std::runtime_error("downgradeToFormat1: not a format 2 manifest");
  manifest.replace(v, 18, "format_version: 1\n");
  const auto layers = manifest.find("\nlayers:\n");
  if (layers != std::string::npos) manifest.resize(layers + 1);
  writeFileBytes(dir / "manifest.yaml", manifest);
  std::filesystem::remove_all(dir / "layers");
}

}  // namespace radarslam::test
