#pragma once
// Random mutations almost never keep a PNG chunk's CRC right, so without help the fuzzer would
// only ever exercise the CRC check. For 7 of 8 inputs (by size) the harness rewrites the CRC of
// every chunk that fits in the data, letting mutated chunk contents reach libpng and our
// decoders; the remaining inputs go in untouched (CRC and structure checks).
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace radarslam::fuzz {

inline std::vector<std::uint8_t> maybeFixPngCrcs(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> b(data, data + size);
  if (size % 8 == 0) return b;
  auto be32 = [&](std::size_t p) {
    return (std::uint32_t{b[p]} << 24) | (std::uint32_t{b[p + 1]} << 16) | (std::uint32_t{b[p + 2]} << 8) |
           b[p + 3];
  };
  std::size_t pos = 8;  // after the signature
  while (pos + 12 <= b.size()) {
    const std::size_t len = be32(pos);
    if (len > b.size() - pos - 12) break;
    const auto crc = static_cast<std::uint32_t>(crc32(0L, &b[pos + 4], static_cast<uInt>(len + 4)));
    for (int k = 0; k < 4; ++k)
      b[pos + 8 + len + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(crc >> (24 - 8 * k));
    pos += 12 + len;
  }
  return b;
}

}  // namespace radarslam::fuzz
