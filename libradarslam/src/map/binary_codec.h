#pragma once
// Little-endian encoding of the map's .bin files (layout in maps/README.md): a Writer appends
// scalars/arrays to a byte string, a Reader consumes them and reports truncation as InputError.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "radarslam/core/errors.h"

namespace radarslam::mapcodec {

static_assert(std::endian::native == std::endian::little,
              "the map format is little-endian; add byte swapping for big-endian hosts");

/// Every .bin file starts with: 8-byte magic, u32 format version, u32 reserved (0), u64 count.
constexpr std::size_t kHeaderBytes = 24;

class Writer {
 public:
  template <class T>
  void put(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void putRaw(const void* p, std::size_t n) { bytes_.append(static_cast<const char*>(p), n); }
  void header(const char (&magic)[9], std::uint32_t version, std::uint64_t count) {
    putRaw(magic, 8);
    put<std::uint32_t>(version);
    put<std::uint32_t>(0);
    put<std::uint64_t>(count);
  }
  const std::string& bytes() const { return bytes_; }
  void reserve(std::size_t n) { bytes_.reserve(n); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  Reader(const std::string& bytes, std::string file) : bytes_(bytes), file_(std::move(file)) {}
  template <class T>
  T get(const char* what) {
    T v;
    getRaw(&v, sizeof v, what);
    return v;
  }
  void getRaw(void* p, std::size_t n, const char* what) {
    if (n > bytes_.size() - pos_)
      throw InputError(file_, std::string("truncated: file ends at byte ")
                                  .append(std::to_string(bytes_.size()))
                                  .append(" while reading ")
                                  .append(what));
    if (n == 0) return;  // p may be an empty vector's data() == nullptr: memcpy(nullptr, .., 0) is UB (UBSan)
    std::memcpy(p, bytes_.data() + pos_, n);
    pos_ += n;
  }
  /// Checks magic and version; returns the record count.
  std::uint64_t header(const char (&magic)[9], std::uint32_t max_version) {
    char m[8];
    getRaw(m, 8, "the file header");
    if (std::memcmp(m, magic, 8) != 0)
      throw InputError(file_, std::string("not a radarslam map file of this kind (bad magic, expected '")
                                  .append(magic)
                                  .append("')"));
    const auto version = get<std::uint32_t>("the format version");
    if (version > max_version)
      throw InputError(file_, "format version " + std::to_string(version) +
                                  " is newer than this radarslam reads (" + std::to_string(max_version) +
                                  "); upgrade radarslam");
    if (version == 0) throw InputError(file_, "invalid format version 0");
    get<std::uint32_t>("the header");
    return get<std::uint64_t>("the record count");
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  const std::string& file() const { return file_; }

 private:
  const std::string& bytes_;
  std::string file_;
  std::size_t pos_ = 0;
};

}  // namespace radarslam::mapcodec
