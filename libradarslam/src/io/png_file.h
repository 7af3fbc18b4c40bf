#pragma once
// Reading 8-bit greyscale PNG files safely. The chunk structure is checked before decoding
// (signature, every chunk's CRC, IHDR first, IEND last and at the very end of the file) because
// libpng decodes a truncated file partially and prints warnings instead of failing: here a
// truncated or corrupt file is always an InputError naming the file.
#include <filesystem>
#include <opencv2/core/mat.hpp>

namespace radarslam::io_detail {

struct PngSize {
  int width = 0;
  int height = 0;
};

/// Width and height from the IHDR chunk, without decoding (throws InputError if not a PNG).
PngSize readPngSize(const std::filesystem::path& file);

/// Checks the PNG structure, decodes it and returns a CV_8UC1 image. Throws InputError
/// (missing file, not a PNG, truncated, CRC mismatch, decode failure, not 8-bit greyscale).
cv::Mat readGreyPng(const std::filesystem::path& file);

}  // namespace radarslam::io_detail
