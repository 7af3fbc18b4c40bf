// SHA-256 through OpenSSL's EVP interface (map/sha256.h).
#include "radarslam/map/sha256.h"

#include <openssl/evp.h>

#include <algorithm>
#include <stdexcept>

#include "manifest_strings.h"

namespace radarslam {

Sha256::Sha256() : ctx_(EVP_MD_CTX_new()) {
  if (!ctx_ || EVP_DigestInit_ex(ctx_, EVP_sha256(), nullptr) != 1) {
    EVP_MD_CTX_free(ctx_);
    throw std::runtime_error("SHA-256: OpenSSL could not initialise a digest");
  }
}

Sha256::~Sha256() { EVP_MD_CTX_free(ctx_); }

void Sha256::update(std::span<const unsigned char> data) {
  if (!data.empty() && EVP_DigestUpdate(ctx_, data.data(), data.size()) != 1)
    throw std::runtime_error("SHA-256: OpenSSL digest update failed");
}

std::array<unsigned char, 32> Sha256::digest() {
  std::array<unsigned char, 32> out{};
  unsigned int n = 0;
  if (EVP_DigestFinal_ex(ctx_, out.data(), &n) != 1 || n != out.size())
    throw std::runtime_error("SHA-256: OpenSSL digest failed");
  return out;
}

std::string Sha256::hexDigest() {
  const auto d = digest();
  return toHex(d);
}

std::string sha256Hex(std::span<const unsigned char> data) {
  Sha256 h;
  h.update(data);
  return h.hexDigest();
}

std::string toHex(std::span<const unsigned char> bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out(2 * bytes.size(), '0');
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    out[2 * i] = digits[bytes[i] >> 4];
    out[2 * i + 1] = digits[bytes[i] & 15];
  }
  return out;
}

bool isSha256Hex(std::string_view text) {
  return text.size() == 64 && text.find_first_not_of("0123456789abcdef") == std::string_view::npos;
}

std::optional<std::array<unsigned char, 32>> sha256FromHex(std::string_view text) {
  if (!isSha256Hex(text)) return std::nullopt;
  const std::optional<std::string> bytes = mapcodec::hexDecode(std::string(text));
  std::array<unsigned char, 32> out{};
  std::copy(bytes->begin(), bytes->end(), out.begin());
  return out;
}

}  // namespace radarslam
