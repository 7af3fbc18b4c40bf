#include "png_file.h"

#include "png_bytes.h"
#include "png_decode.h"

#include <zlib.h>
#include <array>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"
#include "text_util.h"

namespace radarslam::io_detail {

namespace {

constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// CRC-32 as PNG specifies it (ISO 3309) is zlib's crc32 (already linked through libpng), which
// is several times faster than a byte-wise table: it runs over every byte of every scan file.
std::uint32_t crc32(std::span<const unsigned char> data) {
  return static_cast<std::uint32_t>(
      ::crc32(::crc32(0L, Z_NULL, 0), data.data(), static_cast<uInt>(data.size())));
}

void checkSignature(std::span<const unsigned char> bytes, const std::filesystem::path& file) {
  if (bytes.size() < kSignature.size() ||
      std::memcmp(bytes.data(), kSignature.data(), kSignature.size()) != 0)
    throw InputError(file.string(), "not a PNG file (bad signature)");
}

// Walks all chunks: each must fit in the file and have a correct CRC; IHDR first; the file ends
// right after IEND. Returns the IHDR size.
PngSize checkChunks(std::span<const unsigned char> bytes, const std::filesystem::path& file) {
  checkSignature(bytes, file);
  std::size_t pos = kSignature.size();
  PngSize size;
  bool first = true;
  while (true) {
    if (pos + 12 > bytes.size())
      throw InputError(file.string(), "truncated PNG (file ends inside a chunk header, no IEND chunk)");
    const std::uint32_t len = be32(&bytes[pos]);
    const unsigned char* type = &bytes[pos + 4];
    if (len > bytes.size() || pos + 12 + len > bytes.size())
      throw InputError(file.string(), "truncated PNG (a chunk extends past the end of the file)");
    const std::string type_name(reinterpret_cast<const char*>(type), 4);
    const std::uint32_t stored_crc = be32(&bytes[pos + 8 + len]);
    if (crc32(bytes.subspan(pos + 4, len + 4)) != stored_crc)
      throw InputError(file.string(), "corrupt PNG (CRC mismatch in chunk '" + type_name + "' at byte " +
                                          std::to_string(pos) + ")");
    if (first) {
      if (type_name != "IHDR" || len < 8)
        throw InputError(file.string(), "corrupt PNG (first chunk is not IHDR)");
      size.width = static_cast<int>(be32(type + 4));
      size.height = static_cast<int>(be32(type + 8));
      first = false;
    }
    pos += 12 + len;
    if (type_name == "IEND") {
      if (pos != bytes.size()) throw InputError(file.string(), "corrupt PNG (data after the IEND chunk)");
      return size;
    }
  }
}

}  // namespace

PngSize readPngSize(const std::filesystem::path& file) {
  requireRegularFile(file, "cannot open file (missing or unreadable)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "cannot open file (missing or unreadable)");
  std::array<unsigned char, 24> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  if (in.gcount() != static_cast<std::streamsize>(head.size())) {
    checkSignature(std::span<const unsigned char>(head.data(), static_cast<std::size_t>(in.gcount())), file);
    throw InputError(file.string(), "truncated PNG (shorter than its header)");
  }
  checkSignature(head, file);
  if (std::memcmp(&head[12], "IHDR", 4) != 0)
    throw InputError(file.string(), "corrupt PNG (first chunk is not IHDR)");
  return {static_cast<int>(be32(&head[16])), static_cast<int>(be32(&head[20]))};
}

cv::Mat readGreyPng(const std::filesystem::path& file) {
  const std::vector<unsigned char> bytes = readBytes(file);
  const PngSize size = checkChunks(bytes, file);
  if (size.width <= 0 || size.height <= 0) throw InputError(file.string(), "PNG has an empty image");
  // The largest radar scan we know (RAS6) is 400 x 6848 = 2.7 M pixels; a header claiming more
  // than 64 M is corrupt (and OpenCV would throw cv::Exception above its own 1 G limit).
  constexpr long long kMaxPixels = 64LL << 20;
  if (static_cast<long long>(size.width) * size.height > kMaxPixels)
    throw InputError(file.string(), "PNG header claims " + std::to_string(size.width) + " x " +
                                        std::to_string(size.height) + " pixels, more than any radar scan");
  cv::Mat img = decodeGreyPng(bytes.data(), bytes.size(), file);
  if (img.cols != size.width || img.rows != size.height)
    throw InputError(file.string(), "PNG decoded to a different size than its header says");
  return img;
}

}  // namespace radarslam::io_detail
