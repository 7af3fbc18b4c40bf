#include "png_decode.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>

#include "png_fast_decode.h"
#include "radarslam/core/errors.h"

namespace radarslam::io_detail {

namespace {

// Everything the libpng callbacks touch. Plain data: decodeRows() longjmps out of libpng, so no
// object with a destructor may live in its frame.
struct PngSource {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  std::size_t pos = 0;
  char message[200] = {};
};

void onError(png_structp png, png_const_charp msg) {
  auto* src = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(src->message, sizeof(src->message), "%s", msg != nullptr ? msg : "unknown libpng error");
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // warnings are not errors; never printed

void onRead(png_structp png, png_bytep out, png_size_t n) {
  auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (n > src->size - src->pos) png_error(png, "unexpected end of image data");
  std::memcpy(out, src->data + src->pos, n);
  src->pos += n;
}

enum class Decoded { ok, error, not_grey8 };

// Reads the header into (width, height, colour type, bit depth), then, if `out` is non-null,
// the pixels into out (width x height bytes, row-major). Returns error with src.message set.
Decoded decodeRows(PngSource& src, unsigned char* out, png_uint_32& width, png_uint_32& height,
                   int& color_type, int& bit_depth) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, onError, onWarning);
  if (png == nullptr) {
    std::snprintf(src.message, sizeof(src.message), "out of memory in libpng");
    return Decoded::error;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr);
    return Decoded::error;
  }
  png_set_read_fn(png, &src, onRead);
  png_read_info(png, info);
  png_get_IHDR(png, info, &width, &height, &bit_depth, &color_type, nullptr, nullptr, nullptr);
  if (color_type != PNG_COLOR_TYPE_GRAY || bit_depth > 8 || out == nullptr) {
    png_destroy_read_struct(&png, &info, nullptr);
    return color_type != PNG_COLOR_TYPE_GRAY || bit_depth > 8 ? Decoded::not_grey8 : Decoded::ok;
  }
  if (bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  for (int pass = 0; pass < passes; ++pass)
    for (png_uint_32 r = 0; r < height; ++r)
      png_read_row(png, out + static_cast<std::size_t>(r) * width, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return Decoded::ok;
}

[[noreturn]] void notGrey8(const std::filesystem::path& file, int color_type, int bit_depth) {
  throw InputError(file.string(), "expected an 8-bit greyscale PNG, got PNG colour type " +
                                      std::to_string(color_type) + " with " + std::to_string(bit_depth) +
                                      " bits per sample");
}

}  // namespace

cv::Mat decodeGreyPng(const unsigned char* bytes, std::size_t size, const std::filesystem::path& file) {
  constexpr unsigned long long kMaxPixels = 64ULL << 20;  // 25x the largest radar scan (RAS6)
  // The common case (8-bit greyscale, intact) with libdeflate; libpng for the rest and for errors.
  if (cv::Mat fast; decodeGrey8PngFast(bytes, size, kMaxPixels, fast)) return fast;
  PngSource src;
  src.data = bytes;
  src.size = size;
  png_uint_32 width = 0, height = 0;
  int color_type = 0, bit_depth = 0;
  Decoded d = decodeRows(src, nullptr, width, height, color_type, bit_depth);
  if (d == Decoded::not_grey8) notGrey8(file, color_type, bit_depth);
  if (d == Decoded::ok && static_cast<unsigned long long>(width) * height > kMaxPixels)
    throw InputError(file.string(), "PNG claims " + std::to_string(width) + " x " + std::to_string(height) +
                                        " pixels, more than any radar scan");
  if (d == Decoded::ok) {
    cv::Mat img(static_cast<int>(height), static_cast<int>(width), CV_8UC1);
    src.pos = 0;
    d = decodeRows(src, img.data, width, height, color_type, bit_depth);
    if (d == Decoded::ok) return img;
  }
  throw InputError(file.string(), std::string("PNG could not be decoded (") + src.message + ")");
}

}  // namespace radarslam::io_detail
