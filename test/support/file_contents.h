#pragma once
// Whole-file reads and writes for the tests, in binary: the bytes as they are on disk.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

namespace radarslam::test {

/// The file's bytes ("" when it cannot be opened).
inline std::string readFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

/// Replaces the file's contents with `bytes` (creates it if needed).
inline void writeFileBytes(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

}  // namespace radarslam::test
