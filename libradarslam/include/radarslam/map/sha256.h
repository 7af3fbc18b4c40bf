#pragma once
// SHA-256 (FIPS 180-4), used for the per-file checksums of the map format and the DDS layers.
// OpenSSL's implementation (libcrypto: SHA-NI / AVX2 code paths, ~6x our former portable one,
// bench_map BM_Sha256); tested against the FIPS/NIST example vectors.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

struct evp_md_ctx_st;  // OpenSSL's EVP_MD_CTX, kept out of our headers

namespace radarslam {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(std::span<const unsigned char> data);
  void update(std::string_view text) {
    update({reinterpret_cast<const unsigned char*>(text.data()), text.size()});
  }
  /// Finishes the hash; the object must not be updated afterwards.
  std::array<unsigned char, 32> digest();
  /// digest() as 64 lower-case hex characters.
  std::string hexDigest();

 private:
  evp_md_ctx_st* ctx_;
};

std::string sha256Hex(std::span<const unsigned char> data);

/// Bytes as lower-case hex, two digits per byte.
std::string toHex(std::span<const unsigned char> bytes);
/// True for exactly 64 lower-case hex digits: the form of every SHA-256 in a map and its layers.
bool isSha256Hex(std::string_view text);
/// The 32 bytes of a SHA-256 written as isSha256Hex(); nullopt for anything else.
std::optional<std::array<unsigned char, 32>> sha256FromHex(std::string_view text);
inline std::string sha256Hex(std::string_view text) {
  return sha256Hex({reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

}  // namespace radarslam
