// Scans are decoded with libpng directly (src/io/png_decode.cpp): a PNG whose chunks are intact
// (valid CRCs) but whose compressed image data is corrupt is a one-line InputError naming the
// file, and libpng prints nothing of its own ("libpng error: ..." used to precede our message).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "file_contents.h"
#include "io_test_util.h"
#include "png_bytes.h"
#include "radarslam/io/dataset.h"
#include "temp_dir.h"

using namespace radarslam;
using test::expectInputError;

namespace {
std::uint32_t pngCrc(const std::uint8_t* p, std::size_t n) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

using radarslam::io_detail::be32;

// Overwrites `n` bytes in the middle of the first IDAT chunk's data and fixes that chunk's CRC.
void corruptImageData(std::vector<std::uint8_t>& png, std::size_t n) {
  std::size_t pos = 8;
  while (pos + 12 <= png.size()) {
    const std::uint32_t len = be32(&png[pos]);
    if (std::memcmp(&png[pos + 4], "IDAT", 4) == 0) {
      ASSERT_GT(len, n + 8);
      for (std::size_t k = 0; k < n; ++k) png[pos + 8 + len / 2 + k] ^= 0xA5;
      const std::uint32_t crc = pngCrc(&png[pos + 4], len + 4);
      for (int k = 0; k < 4; ++k)
        png[pos + 8 + len + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(crc >> (24 - 8 * k));
      return;
    }
    pos += 12 + len;
  }
  FAIL() << "no IDAT chunk";
}

std::filesystem::path radiateScan(const test::TempDir& tmp) {
  test::writeText(tmp / "radiate" / "Navtech_Polar.txt",
                  "Frame: 000001 Time: 1574859771.744660272\nFrame: 000002 Time: 1574859771.977525228\n");
  return tmp / "radiate" / "Navtech_Polar" / "000001.png";
}
}  // namespace

TEST(PngDecode, DecodesWhatOpenCvWroteExactly) {
  test::TempDir tmp;
  const auto png = radiateScan(tmp);
  test::writeTransposedPng(png, 16, 64);
  ::testing::internal::CaptureStderr();
  const auto scan = readScanFile(png);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  ASSERT_NE(scan, nullptr);
  ASSERT_EQ(scan->num_azimuths, 16u);
  ASSERT_EQ(scan->num_bins, 64u);
  for (int a = 0; a < 16; ++a)
    for (int b = 0; b < 64; ++b)
      ASSERT_EQ(scan->row(static_cast<std::size_t>(a))[static_cast<std::size_t>(b)],
                test::syntheticPower(a, b))
          << "azimuth " << a << " bin " << b;
}

TEST(PngDecode, CorruptImageDataIsOneErrorAndNoLibpngOutput) {
  test::TempDir tmp;
  const auto png = radiateScan(tmp);
  test::writeTransposedPng(png, 64, 256);
  const std::string file = test::readFileBytes(png);
  std::vector<std::uint8_t> bytes(file.begin(), file.end());
  corruptImageData(bytes, 24);
  test::writeFileBytes(png, std::string(bytes.begin(), bytes.end()));
  ::testing::internal::CaptureStderr();
  expectInputError([&] { (void)readScanFile(png); }, "000001.png", "PNG could not be decoded");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(PngDecode, ColourImageIsRejectedNamingTheFile) {
  test::TempDir tmp;
  const auto png = radiateScan(tmp);
  std::filesystem::create_directories(png.parent_path());
  ASSERT_TRUE(cv::imwrite(png.string(), cv::Mat(64, 16, CV_8UC3, cv::Scalar(1, 2, 3))));
  expectInputError([&] { (void)readScanFile(png); }, "000001.png", "8-bit greyscale");
  ASSERT_TRUE(cv::imwrite(png.string(), cv::Mat(64, 16, CV_16UC1, cv::Scalar(300))));
  expectInputError([&] { (void)readScanFile(png); }, "000001.png", "16 bits per sample");
}
