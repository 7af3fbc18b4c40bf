// The libdeflate PNG path (src/io/png_fast_decode.h) decodes exactly what libpng (through OpenCV)
// decodes, for every row filter and for every real scan in ../shared, and declines (so libpng
// reports) anything it does not handle or finds wrong.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "file_contents.h"
#include "png_fast_decode.h"
#include "shared_data.h"

using radarslam::io_detail::decodeGrey8PngFast;

namespace {

using Bytes = std::vector<unsigned char>;
constexpr unsigned long long kMaxPixels = 64ULL << 20;

void put32(Bytes& b, std::uint32_t v) {
  for (int k = 3; k >= 0; --k) b.push_back(static_cast<unsigned char>(v >> (8 * k)));
}

void chunk(Bytes& png, const char* type, const Bytes& data) {
  put32(png, static_cast<std::uint32_t>(data.size()));
  Bytes body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  png.insert(png.end(), body.begin(), body.end());
  put32(png, static_cast<std::uint32_t>(crc32(0, body.data(), static_cast<uInt>(body.size()))));
}

Bytes ihdr(std::uint32_t w, std::uint32_t h, unsigned char depth = 8, unsigned char colour = 0,
           unsigned char interlace = 0) {
  Bytes d;
  put32(d, w);
  put32(d, h);
  d.insert(d.end(), {depth, colour, 0, 0, interlace});
  return d;
}

// An 8-bit greyscale PNG of `img` whose row r uses filter filters[r % filters.size()] (PNG spec
// Sec. 9: filtered = raw - predictor), the zlib stream split into IDAT chunks of `idat_size`.
Bytes encode(const cv::Mat& img, const std::vector<int>& filters, std::size_t idat_size = 8192) {
  const int w = img.cols, h = img.rows;
  Bytes raw;
  for (int r = 0; r < h; ++r) {
    const int f = filters[static_cast<std::size_t>(r) % filters.size()];
    raw.push_back(static_cast<unsigned char>(f));
    for (int c = 0; c < w; ++c) {
      const int x = img.at<unsigned char>(r, c);
      const int a = c > 0 ? img.at<unsigned char>(r, c - 1) : 0;
      const int b = r > 0 ? img.at<unsigned char>(r - 1, c) : 0;
      const int cc = r > 0 && c > 0 ? img.at<unsigned char>(r - 1, c - 1) : 0;
      int pred = 0;
      if (f == 1) pred = a;
      if (f == 2) pred = b;
      if (f == 3) pred = (a + b) / 2;
      if (f == 4) {
        const int p = a + b - cc, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - cc);
        pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : cc;
      }
      raw.push_back(static_cast<unsigned char>(x - pred));
    }
  }
  uLongf n = compressBound(static_cast<uLong>(raw.size()));
  Bytes z(n);
  EXPECT_EQ(compress2(z.data(), &n, raw.data(), static_cast<uLong>(raw.size()), 6), Z_OK);
  z.resize(n);
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  chunk(png, "IHDR", ihdr(static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)));
  chunk(png, "tEXt", Bytes{'a', 0, 'b'});  // an ancillary chunk is skipped
  for (std::size_t at = 0; at < z.size(); at += idat_size)
    chunk(png, "IDAT",
          Bytes(z.begin() + static_cast<long>(at),
                z.begin() + static_cast<long>(std::min(z.size(), at + idat_size))));
  chunk(png, "IEND", {});
  return png;
}

cv::Mat speckle(int h, int w, unsigned seed) {
  cv::Mat img(h, w, CV_8UC1);
  std::mt19937 rng(seed);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) img.at<unsigned char>(r, c) = static_cast<unsigned char>(rng() % 256);
  return img;
}

bool sameImage(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

}  // namespace

TEST(PngFastDecode, EveryFilterDecodesAsLibpngDoes) {
  const cv::Mat img = speckle(37, 53, 7);
  for (const std::vector<int>& filters :
       std::vector<std::vector<int>>{{0}, {1}, {2}, {3}, {4}, {0, 1, 2, 3, 4}, {4, 3, 2, 1}}) {
    for (const std::size_t idat : {std::size_t{100000}, std::size_t{97}}) {
      const Bytes png = encode(img, filters, idat);
      cv::Mat fast;
      ASSERT_TRUE(decodeGrey8PngFast(png.data(), png.size(), kMaxPixels, fast));
      EXPECT_TRUE(sameImage(fast, img)) << "filters " << filters.front() << ", IDAT size " << idat;
      const cv::Mat reference = cv::imdecode(png, cv::IMREAD_UNCHANGED);
      EXPECT_TRUE(sameImage(fast, reference));
    }
  }
}

TEST(PngFastDecode, EveryRealScanDecodesAsLibpngDoes) {
  RADARSLAM_REQUIRE_REAL_DATA(real, "");
  std::size_t n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(real)) {
    if (e.path().extension() != ".png") continue;
    const std::string file = radarslam::test::readFileBytes(e.path());
    const Bytes png(file.begin(), file.end());
    const cv::Mat reference = cv::imdecode(png, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(reference.type(), CV_8UC1) << e.path();
    cv::Mat fast;
    ASSERT_TRUE(decodeGrey8PngFast(png.data(), png.size(), kMaxPixels, fast)) << e.path();
    EXPECT_TRUE(sameImage(fast, reference)) << e.path();
    ++n;
  }
  EXPECT_GE(n, 48u);  // Oxford (12), RADIATE polar and Cartesian (36)
}

TEST(PngFastDecode, DeclinesWhatItDoesNotHandleOrFindsWrong) {
  const cv::Mat img = speckle(20, 30, 3);
  const Bytes good = encode(img, {1, 4});
  cv::Mat out;
  ASSERT_TRUE(decodeGrey8PngFast(good.data(), good.size(), kMaxPixels, out));
  const auto declines = [&](const Bytes& png, const std::string& why) {
    cv::Mat o;
    EXPECT_FALSE(decodeGrey8PngFast(png.data(), png.size(), kMaxPixels, o)) << why;
  };
  // Every truncation (the last chunk is IEND: without it the file is incomplete).
  for (std::size_t n = 0; n < good.size(); ++n)
    declines(Bytes(good.begin(), good.begin() + static_cast<long>(n)), "truncated to " + std::to_string(n));
  // A flipped bit anywhere after the signature breaks a CRC, the zlib stream or its Adler-32.
  for (std::size_t at = 8; at < good.size(); at += 7) {
    Bytes bad = good;
    bad[at] ^= 0x10;
    declines(bad, "bit flipped at byte " + std::to_string(at));
  }
  const auto withHeader = [&](const Bytes& header) {
    Bytes png(good.begin(), good.begin() + 8);
    chunk(png, "IHDR", header);
    png.insert(png.end(), good.begin() + 8 + 25, good.end());  // the rest after the original IHDR
    return png;
  };
  declines(withHeader(ihdr(30, 20, 16)), "16-bit");
  declines(withHeader(ihdr(30, 20, 4)), "4-bit");
  declines(withHeader(ihdr(30, 20, 8, 2)), "colour");
  declines(withHeader(ihdr(30, 20, 8, 0, 1)), "interlaced");
  declines(withHeader(ihdr(30, 19)), "one row more data than the header says");
  declines(withHeader(ihdr(31, 20)), "less data than the header says");
  cv::Mat o;
  EXPECT_FALSE(decodeGrey8PngFast(good.data(), good.size(), 599, o)) << "more pixels than allowed";
  // A palette, or a critical chunk it does not know, before the image data.
  for (const char* type : {"PLTE", "ABCD"}) {
    Bytes png(good.begin(), good.begin() + 8 + 25);
    chunk(png, type, Bytes{1, 2, 3});
    png.insert(png.end(), good.begin() + 8 + 25, good.end());
    declines(png, type);
  }
  // Row filter type 5 does not exist.
  Bytes raw;
  for (int r = 0; r < 2; ++r) raw.insert(raw.end(), {5, 1, 2});
  uLongf n = compressBound(6);
  Bytes z(n);
  ASSERT_EQ(compress2(z.data(), &n, raw.data(), 6, 6), Z_OK);
  z.resize(n);
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  chunk(png, "IHDR", ihdr(2, 2));
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  declines(png, "filter type 5");
}
