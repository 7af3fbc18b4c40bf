#pragma once
// SHA-256 (FIPS 180-4), used for the per-file checksums of the map format. Small and dependency
// free; tested against the FIPS/NIST example vectors.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace radarslam {

class Sha256 {
 public:
  Sha256();
  void update(std::span<const unsigned char> data);
  void update(std::string_view text) {
    update({reinterpret_cast<const unsigned char*>(text.data()), text.size()});
  }
  /// Finishes the hash; the object must not be updated afterwards.
  std::array<unsigned char, 32> digest();
  /// digest() as 64 lower-case hex characters.
  std::string hexDigest();

 private:
  void block(const unsigned char* p);
  std::array<std::uint32_t, 8> h_;
  std::array<unsigned char, 64> buf_{};
  std::size_t buf_len_ = 0;
  std::uint64_t total_bytes_ = 0;
};

std::string sha256Hex(std::span<const unsigned char> data);
inline std::string sha256Hex(std::string_view text) {
  return sha256Hex({reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

}  // namespace radarslam
