#include "png_fast_decode.h"
#include "png_bytes.h"

#include <libdeflate.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

namespace radarslam::io_detail {

namespace {

bool isCritical(const unsigned char* type) { return (type[0] & 0x20) == 0; }  // upper-case first letter

// PNG spec (2003) Sec. 9.4: the Paeth predictor.
inline unsigned char paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return static_cast<unsigned char>(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// Reverses one row's filter (one byte per pixel): `raw` is the filtered row, `prev` the row
// above as decoded (zeros for the first row). Returns false for an unknown filter type.
bool unfilterRow(int type, const unsigned char* raw, const unsigned char* prev, unsigned char* row,
                 std::size_t width) {
  switch (type) {
    case 0:
      std::memcpy(row, raw, width);
      return true;
    case 1: {
      unsigned char left = 0;
      for (std::size_t i = 0; i < width; ++i) row[i] = left = static_cast<unsigned char>(raw[i] + left);
      return true;
    }
    case 2:
      for (std::size_t i = 0; i < width; ++i) row[i] = static_cast<unsigned char>(raw[i] + prev[i]);
      return true;
    case 3: {
      int left = 0;
      for (std::size_t i = 0; i < width; ++i)
        left = row[i] = static_cast<unsigned char>(raw[i] + ((left + prev[i]) >> 1));
      return true;
    }
    case 4: {
      int left = 0, upper_left = 0;
      for (std::size_t i = 0; i < width; ++i) {
        left = row[i] = static_cast<unsigned char>(raw[i] + paeth(left, prev[i], upper_left));
        upper_left = prev[i];
      }
      return true;
    }
    default:
      return false;
  }
}

struct DecompressorDeleter {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

}  // namespace

bool decodeGrey8PngFast(const unsigned char* bytes, std::size_t size, unsigned long long max_pixels,
                        cv::Mat& out) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size < 8 || std::memcmp(bytes, kSignature, 8) != 0) return false;
  std::size_t pos = 8;
  std::uint32_t width = 0, height = 0;
  bool have_header = false, have_end = false;
  // The image data: IDAT chunks' payloads, in order (most files split it into 8 KiB chunks).
  std::vector<std::pair<const unsigned char*, std::size_t>> idat;
  std::size_t idat_bytes = 0;
  while (!have_end) {
    if (size - pos < 12) return false;  // a chunk needs length, type and CRC
    const std::uint32_t length = be32(bytes + pos);
    if (length > 0x7FFFFFFFu || length > size - pos - 12) return false;
    const unsigned char* type = bytes + pos + 4;
    const unsigned char* data = type + 4;
    if (libdeflate_crc32(0, type, length + 4) != be32(data + length)) return false;
    if (!have_header) {
      // IHDR first: 8-bit (8) greyscale (0), deflate (0), adaptive filtering (0), no interlace (0).
      if (std::memcmp(type, "IHDR", 4) != 0 || length != 13) return false;
      width = be32(data);
      height = be32(data + 4);
      if (width == 0 || height == 0 || data[8] != 8 || data[9] != 0 || data[10] != 0 || data[11] != 0 ||
          data[12] != 0)
        return false;
      if (static_cast<unsigned long long>(width) * height > max_pixels) return false;
      have_header = true;
    } else if (std::memcmp(type, "IDAT", 4) == 0) {
      idat.emplace_back(data, length);
      idat_bytes += length;
    } else if (std::memcmp(type, "IEND", 4) == 0) {
      have_end = true;
    } else if (isCritical(type)) {
      return false;  // IHDR again, PLTE (not allowed in greyscale) or a critical chunk we do not know
    }
    pos += 12 + static_cast<std::size_t>(length);
  }
  if (idat.empty()) return false;

  const unsigned char* stream = idat.front().first;
  std::vector<unsigned char> joined;
  if (idat.size() > 1) {
    joined.resize(idat_bytes);
    std::size_t at = 0;
    for (const auto& [p, n] : idat) {
      std::memcpy(joined.data() + at, p, n);
      at += n;
    }
    stream = joined.data();
  }
  const std::size_t stride = static_cast<std::size_t>(width) + 1;  // filter byte + row
  std::vector<unsigned char> filtered(stride * height);
  thread_local std::unique_ptr<libdeflate_decompressor, DecompressorDeleter> inflater(
      libdeflate_alloc_decompressor());
  if (!inflater) return false;
  // Without an actual-size argument libdeflate succeeds only when the stream inflates to exactly
  // the buffer's size; it checks the zlib header and the Adler-32 of the data.
  if (libdeflate_zlib_decompress(inflater.get(), stream, idat_bytes, filtered.data(), filtered.size(),
                                 nullptr) != LIBDEFLATE_SUCCESS)
    return false;

  out.create(static_cast<int>(height), static_cast<int>(width), CV_8UC1);
  std::vector<unsigned char> zeros(width, 0);
  const unsigned char* prev = zeros.data();
  for (std::uint32_t r = 0; r < height; ++r) {
    const unsigned char* raw = filtered.data() + static_cast<std::size_t>(r) * stride;
    unsigned char* row = out.ptr<unsigned char>(static_cast<int>(r));
    if (!unfilterRow(raw[0], raw + 1, prev, row, width)) return false;
    prev = row;
  }
  return true;
}

}  // namespace radarslam::io_detail
