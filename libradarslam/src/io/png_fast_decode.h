#pragma once
// The common radar PNG (8-bit greyscale, not interlaced) decoded with libdeflate instead of
// libpng + zlib: chunk CRCs (libdeflate_crc32), one whole-buffer inflate with its Adler-32 check,
// and the five PNG row filters. On the real Oxford scans it takes ~half the time of libpng
// (bench_io BM_DecodeOxfordPng: 11.2 -> 5.2 ms/scan). Anything it does not handle, or finds wrong, it
// declines, and decodeGreyPng() then decodes with libpng, which reports the error in its own words.
#include <cstddef>
#include <opencv2/core/mat.hpp>

namespace radarslam::io_detail {

/// Decodes `bytes` (a whole PNG file) into `out` (CV_8UC1) and returns true when the image is
/// 8-bit greyscale, not interlaced, at most `max_pixels` pixels, and every check passes: the
/// signature, every chunk's CRC, IHDR first, IEND last, no palette or unknown critical chunk, the
/// zlib stream (Adler-32) inflating to exactly one filter byte plus one row per row, and every
/// filter type in 0..4. Returns false otherwise (out is then unspecified).
bool decodeGrey8PngFast(const unsigned char* bytes, std::size_t size, unsigned long long max_pixels,
                        cv::Mat& out);

}  // namespace radarslam::io_detail
