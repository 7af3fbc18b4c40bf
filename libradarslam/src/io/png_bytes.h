#pragma once
// Byte order of the PNG format (PNG spec (2003) Sec. 7.1: integers are big-endian, "network byte
// order"), shared by the chunk checker and the fast decoder.
#include <cstdint>

namespace radarslam::io_detail {

/// The 4-byte big-endian unsigned integer at `p`.
inline std::uint32_t be32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

}  // namespace radarslam::io_detail
