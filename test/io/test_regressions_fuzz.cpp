// Regression tests for inputs found by the sanitizers / fuzzers (docs/hardening.md, test/fuzz/):
// each bad file is an InputError naming the file, never another exception or undefined behaviour.
#include <gtest/gtest.h>

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/ground_truth.h"
#include "radarslam/io/trajectory_files.h"
#include "temp_dir.h"

using namespace radarslam;
using test::expectInputError;

namespace {
// A one-scan plain (uncompressed) rawlog: a 7 x 13 scan labelled "radar".
std::vector<std::uint8_t> oneScanRawlog() {
  auto scan = CObservationRadarScan::Create();
  scan->resize(7, 13);
  scan->sensorLabel = "radar";
  mrpt::io::CMemoryStream mem;
  mrpt::serialization::archiveFrom(mem).WriteObject(scan.get());
  const auto* p = static_cast<const std::uint8_t*>(mem.getRawBufferData());
  return {p, p + mem.getTotalBytesCount()};
}

// Overwrites the first occurrence of `find` in `bytes` with `replace` (same length).
void patch(std::vector<std::uint8_t>& bytes, const std::string& find, const std::string& replace) {
  const auto it = std::search(bytes.begin(), bytes.end(), find.begin(), find.end());
  ASSERT_NE(it, bytes.end()) << "pattern not found in the serialized scan";
  std::memcpy(&*it, replace.data(), replace.size());
}

void writeBytes(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}
}  // namespace

// Microsecond stamps whose ns count overflows int64 (x1000 was signed overflow, UBSan).
TEST(IoRegressionsFuzz, OxfordOdometryStampOutOfRange) {
  test::TempDir tmp;
  const auto csv = tmp / "radar_odometry.csv";
  writeText(csv,
            "source_timestamp,destination_timestamp,x,y,z,roll,pitch,yaw,source_radar_timestamp,"
            "destination_radar_timestamp\n"
            "9999999999999999,1547120788016733,0.5,0,0,0,0,0,1547120788141733,1547120787891733\n");
  expectInputError([&] { readOxfordGroundTruth(csv); }, "radar_odometry.csv:2", "source_timestamp");
}

TEST(IoRegressionsFuzz, OxfordRadarTimestampOutOfRange) {
  test::TempDir tmp;
  std::filesystem::create_directories(tmp / "radar");
  writeText(tmp / "radar.timestamps", "1547120788016733 1\n-9999999999999999 1\n");
  expectInputError([&] { openDataset(tmp.path()); }, "radar.timestamps:2", "timestamp");
}

// A 19-digit stamp above INT64_MAX: std::stoll threw std::out_of_range through every parser.
TEST(IoRegressionsFuzz, NineteenDigitStampAboveInt64) {
  test::TempDir tmp;
  const auto gt = tmp / "global_pose.csv";
  writeText(gt, "9999999999999999999,1,0,0,10,0,1,0,20,0,0,1,5\n");
  expectInputError([&] { readMulRanGroundTruth(gt); }, "global_pose.csv:1", "timestamp");
  const auto tum = tmp / "poses.tum";
  writeText(tum, "9999999999999999999 0 0 0 0 0 0 1\n");
  expectInputError([&] { readTumTrajectory(tum); }, "poses.tum:1", "timestamp");
}

// Decimal seconds with 10 integer digits whose ns count overflows int64.
TEST(IoRegressionsFuzz, DecimalSecondsOutOfRange) {
  test::TempDir tmp;
  const auto tum = tmp / "poses.tum";
  writeText(tum, "9999999999.5 0 0 0 0 0 0 1\n");
  expectInputError([&] { readTumTrajectory(tum); }, "poses.tum:1", "timestamp");
  writeText(tmp / "Navtech_Polar.txt", "Frame: 000001 Time: 9999999999.5\n");
  std::filesystem::create_directories(tmp / "Navtech_Polar");
  expectInputError([&] { openDataset(tmp.path()); }, "Navtech_Polar.txt:1", "malformed line");
}

// A corrupt label length (uint32 from the file) made MRPT's string reader allocate and zero up to
// 4 GB before failing (fuzz_rawlog timeout). Now bounded: a one-line InputError at once.
TEST(IoRegressionsFuzz, RawlogHugeLabelLength) {
  test::TempDir tmp;
  auto bytes = oneScanRawlog();
  patch(bytes, std::string("\x05\0\0\0radar", 9), std::string("\0\xff\xff\xff", 4));
  writeBytes(tmp / "bad.rawlog", bytes);
  expectInputError([&] { openDataset(tmp / "bad.rawlog"); }, "bad.rawlog", "label");
}

// Sizes within the per-dimension limits whose product is a 1 GB scan are rejected before allocating.
TEST(IoRegressionsFuzz, RawlogHugeScanSize) {
  test::TempDir tmp;
  auto bytes = oneScanRawlog();
  patch(bytes, std::string("\x07\0\0\0\x0d\0\0\0", 8), std::string("\0\x40\0\0\0\0\x01\0", 8));
  writeBytes(tmp / "big.rawlog", bytes);
  expectInputError([&] { openDataset(tmp / "big.rawlog"); }, "big.rawlog", "implausible size");
}

// A PNG whose IHDR claims 24688 x 66416 pixels (valid CRCs): OpenCV's decoder threw cv::Exception
// (CV_IO_MAX_IMAGE_PIXELS), which escaped as a non-InputError (found by fuzz_polar_png_transposed).
TEST(IoRegressionsFuzz, PngHeaderClaimingAHugeImage) {
  test::TempDir tmp;
  writeText(tmp / "radiate" / "Navtech_Polar.txt",
            "Frame: 000001 Time: 1574859771.744660272\nFrame: 000002 Time: 1574859771.977525228\n");
  const auto png = tmp / "radiate" / "Navtech_Polar" / "000001.png";
  test::writeTransposedPng(png, 8, 16);
  std::ifstream in(png, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  ASSERT_GE(bytes.size(), 33u);
  // IHDR data at bytes 16..28 (width, height big-endian), its CRC over bytes 12..28 at 29..32.
  const std::uint8_t dims[8] = {0x00, 0x00, 0x60, 0x70, 0x00, 0x01, 0x03, 0x70};
  std::copy(dims, dims + 8, bytes.begin() + 16);
  std::uint32_t crc = 0xFFFFFFFFu;  // CRC-32 (PNG, ISO 3309)
  for (std::size_t i = 12; i < 29; ++i) {
    crc ^= bytes[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  crc ^= 0xFFFFFFFFu;
  for (int k = 0; k < 4; ++k)
    bytes[29 + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(crc >> (24 - 8 * k));
  writeBytes(png, bytes);
  expectInputError([&] { (void)readScanFile(png); }, "000001.png", "more than any radar scan");
}
