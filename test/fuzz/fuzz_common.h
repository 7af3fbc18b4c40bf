#pragma once
// Shared harness for the libFuzzer targets (docs/hardening.md). Every target feeds the fuzzer's
// bytes to one parser of outside data. A radarslam::InputError is the expected answer to bad
// input; any other exception escapes LLVMFuzzerTestOneInput, reaches std::terminate and is
// reported by libFuzzer as a crash, like a sanitizer report, a hang or running out of memory.
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"

namespace radarslam::fuzz {

/// A private scratch directory for this process (parsers that only take a path read from here).
inline const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("radarslam-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

inline void writeFile(const std::filesystem::path& file, const std::uint8_t* data, std::size_t size) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + file.string());
}

inline void writeText(const std::filesystem::path& file, std::string_view text) {
  writeFile(file, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

/// Runs `parse`, accepting InputError as the answer to bad input; everything else escapes.
template <class F>
void expectOnlyInputError(F&& parse) {
  try {
    parse();
  } catch (const radarslam::InputError&) {
  }
}

/// Reads fields from the fuzzer's bytes; past the end, what is left (zeros, shorter arrays).
class ByteReader {
 public:
  ByteReader(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
  bool empty() const { return n_ == 0; }
  template <class T>
  T get() {
    T v{};
    const std::size_t k = std::min(sizeof v, n_);
    std::memcpy(&v, d_, k);
    d_ += k, n_ -= k;
    return v;
  }
  template <class T>
  std::vector<T> array(std::size_t count) {
    count = std::min(count, n_ / sizeof(T));
    std::vector<T> out(count);
    if (count > 0) std::memcpy(out.data(), d_, count * sizeof(T));
    d_ += count * sizeof(T), n_ -= count * sizeof(T);
    return out;
  }
  std::string text(std::size_t count) {
    const auto chars = array<char>(count);
    return {chars.begin(), chars.end()};
  }

 private:
  const std::uint8_t* d_;
  std::size_t n_;
};

/// Call once from LLVMFuzzerInitialize: warnings for odd-but-valid input would flood stderr.
inline void quietLogger() { radarslam::logger().setMinLoggingLevel(mrpt::system::LVL_ERROR); }

}  // namespace radarslam::fuzz
