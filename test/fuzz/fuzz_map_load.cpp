// Fuzz target: the map loader (loadMap on a map directory, format in maps/README.md).
// The input is the map directory's five files joined by kPartSeparator, in the order manifest.yaml,
// parameters.yaml, keyframes.bin, points.bin, graph.bin (missing parts = missing files). Random
// mutations would almost never keep the manifest's SHA-256 and byte counts right, so for 7 of 8
// inputs (by size) the harness rewrites the k-th `bytes:` and `sha256:` values of the manifest to
// match part k+1 and lets mutated binary records reach the decoders.
#include <array>
#include <string>
#include <vector>

#include "fuzz_common.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"

namespace {

constexpr std::string_view kPartSeparator = "\n=RSLM-PART=\n";
constexpr std::array<const char*, 5> kNames = {"manifest.yaml", "parameters.yaml", "keyframes.bin",
                                               "points.bin", "graph.bin"};

std::vector<std::string> splitParts(std::string_view in) {
  std::vector<std::string> parts;
  while (parts.size() + 1 < kNames.size()) {
    const auto at = in.find(kPartSeparator);
    if (at == std::string_view::npos) break;
    parts.emplace_back(in.substr(0, at));
    in.remove_prefix(at + kPartSeparator.size());
  }
  parts.emplace_back(in);
  return parts;
}

// Replaces the value after the n-th occurrence of `key` (up to the end of its line).
void replaceNth(std::string& text, std::string_view key, std::size_t n, const std::string& value) {
  std::size_t at = 0;
  for (std::size_t i = 0;; ++i, at += key.size()) {
    at = text.find(key, at);
    if (at == std::string::npos) return;
    if (i == n) break;
  }
  const std::size_t begin = at + key.size();
  const std::size_t end = std::min(text.find('\n', begin), text.size());
  text.replace(begin, end - begin, value);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto dir = radarslam::fuzz::scratchDir() / "map";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::filesystem::remove_all(radarslam::mapBackupDir(dir), ec);
  std::filesystem::create_directories(dir);
  auto parts = splitParts({reinterpret_cast<const char*>(data), size});
  if (size % 8 != 0) {
    for (std::size_t k = 1; k < parts.size(); ++k) {
      replaceNth(parts[0], "bytes:", k - 1, " " + std::to_string(parts[k].size()));
      replaceNth(parts[0], "sha256:", k - 1, " \"" + radarslam::sha256Hex(parts[k]) + "\"");
    }
  }
  for (std::size_t k = 0; k < parts.size(); ++k) radarslam::fuzz::writeText(dir / kNames[k], parts[k]);
  radarslam::fuzz::expectOnlyInputError([&] { (void)radarslam::loadMap(dir); });
  return 0;
}
