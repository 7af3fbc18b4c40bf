#pragma once
// Decoding an 8-bit greyscale PNG held in memory with libpng directly, with our own error and
// warning handlers: libpng's default handlers print "libpng error: ..." to stderr (which
// cv::imdecode lets through), so a corrupt scan would print lines besides our one-line error.
#include <cstddef>
#include <filesystem>
#include <opencv2/core/mat.hpp>

namespace radarslam::io_detail {

/// Decodes `bytes` (a whole PNG file) to CV_8UC1. Greyscale of 1, 2, 4 or 8 bits is accepted
/// (low bit depths are expanded to 8); colour, alpha or 16-bit images and every libpng error
/// throw InputError naming `file`. Nothing is printed.
cv::Mat decodeGreyPng(const unsigned char* bytes, std::size_t size, const std::filesystem::path& file);

}  // namespace radarslam::io_detail
