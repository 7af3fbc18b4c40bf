#pragma once
// Helpers for the io tests: synthetic polar PNGs in the exact dataset layouts, and copies of
// real data into a TempDir that a test may then damage.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "file_contents.h"
#include "radarslam/core/errors.h"

namespace radarslam::test {

/// Power value written into synthetic scans at (azimuth, bin): recognisable and non-trivial.
inline std::uint8_t syntheticPower(int azimuth, int bin) {
  return static_cast<std::uint8_t>((azimuth * 7 + bin * 3) % 251);
}

/// Writes an Oxford-layout PNG: one row per azimuth, int64 LE stamp, uint16 LE encoder, valid byte, bins.
inline void writeOxfordStylePng(const std::filesystem::path& file, const std::vector<std::int64_t>& stamps,
                                const std::vector<std::uint16_t>& encoders,
                                const std::vector<std::uint8_t>& valid, int bins) {
  cv::Mat img(static_cast<int>(stamps.size()), 11 + bins, CV_8UC1);
  for (int r = 0; r < img.rows; ++r) {
    auto* p = img.ptr<std::uint8_t>(r);
    for (int b = 0; b < 8; ++b)
      p[b] = static_cast<std::uint8_t>((static_cast<std::uint64_t>(stamps[r]) >> (8 * b)) & 0xff);
    p[8] = static_cast<std::uint8_t>(encoders[r] & 0xff);
    p[9] = static_cast<std::uint8_t>(encoders[r] >> 8);
    p[10] = valid[r];
    for (int k = 0; k < bins; ++k) p[11 + k] = syntheticPower(r, k);
  }
  std::filesystem::create_directories(file.parent_path());
  ASSERT_TRUE(cv::imwrite(file.string(), img));
}

/// A uniform sweep: `rows` azimuths, stamps step_us apart starting at t0 (in the unit of t0),
/// encoders 14 counts apart starting at `first_encoder`.
struct SyntheticSweep {
  std::vector<std::int64_t> stamps;
  std::vector<std::uint16_t> encoders;
  std::vector<std::uint8_t> valid;
};
inline SyntheticSweep makeSweep(int rows, std::int64_t t0, std::int64_t step,
                                std::uint16_t first_encoder = 7) {
  SyntheticSweep s;
  for (int r = 0; r < rows; ++r) {
    s.stamps.push_back(t0 + r * step);
    s.encoders.push_back(static_cast<std::uint16_t>((first_encoder + 14 * r) % 5600));
    s.valid.push_back(r % 2 ? 255 : 0);
  }
  return s;
}

/// Writes a transposed polar PNG (rows = bins, cols = azimuths).
inline void writeTransposedPng(const std::filesystem::path& file, int azimuths, int bins) {
  cv::Mat img(bins, azimuths, CV_8UC1);
  for (int b = 0; b < bins; ++b)
    for (int a = 0; a < azimuths; ++a) img.at<std::uint8_t>(b, a) = syntheticPower(a, b);
  std::filesystem::create_directories(file.parent_path());
  ASSERT_TRUE(cv::imwrite(file.string(), img));
}

/// writeFileBytes, creating the parent directories first.
inline void writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  writeFileBytes(file, text);
}

inline std::string readText(const std::filesystem::path& file) { return readFileBytes(file); }

/// Copies a directory tree, making the copies writable (the real data is read-only).
inline void copyTree(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::filesystem::copy(from, to, std::filesystem::copy_options::recursive);
  for (const auto& e : std::filesystem::recursive_directory_iterator(to))
    std::filesystem::permissions(e.path(), std::filesystem::perms::owner_write,
                                 std::filesystem::perm_options::add);
  std::filesystem::permissions(to, std::filesystem::perms::owner_write, std::filesystem::perm_options::add);
}

/// Runs `f`, expecting an InputError whose where() contains `where_part` and whose message
/// contains `what_part`; returns the message (for more checks).
inline std::string expectInputError(const std::function<void()>& f, const std::string& where_part,
                                    const std::string& what_part) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_NE(e.where().find(where_part), std::string::npos) << "where() = " << e.where();
    EXPECT_NE(std::string(e.what()).find(what_part), std::string::npos) << "what() = " << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "message is not one line: " << e.what();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError containing '" << what_part << "', nothing thrown";
  return {};
}

}  // namespace radarslam::test
