// Every kind of bad input is a one-line InputError naming the file and the problem. The bad
// files are made in a TempDir from copies of the real Oxford data (never committed).
#include <gtest/gtest.h>

#include <fstream>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/ground_truth.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;
using test::expectInputError;

namespace {

class OxfordCopy : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto src = test::realDataDir() / "oxford_radar_robotcar_tiny";
    if (!std::filesystem::exists(src)) {
      if (test::inCI()) FAIL() << "real data missing in CI: " << src;
      GTEST_SKIP() << "real data not found at " << src;
    }
    root_ = tmp_ / "oxford";
    test::copyTree(src, root_);
    std::filesystem::remove_all(root_ / "gps");  // not needed, keeps the copy small
  }
  std::filesystem::path scan(std::size_t i) const {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(root_ / "radar")) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files.at(i);
  }
  test::TempDir tmp_;
  std::filesystem::path root_;
};

std::string replaceLine(const std::string& text, std::size_t line_index, const std::string& new_line) {
  std::istringstream in(text);
  std::string out, line;
  for (std::size_t i = 0; std::getline(in, line); ++i)
    out.append(i == line_index ? new_line : line).append("\n");
  return out;
}

}  // namespace

TEST_F(OxfordCopy, TruncatedPngIsAnErrorWithoutLibpngNoise) {
  const auto file = scan(3);
  std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
  const auto reader = openDataset(root_);
  ::testing::internal::CaptureStderr();
  expectInputError([&] { reader->readScan(3); }, file.string(), "truncated PNG");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  // Even a file missing only its last bytes (IEND) is caught.
  std::filesystem::resize_file(scan(4), std::filesystem::file_size(scan(4)) - 3);
  expectInputError([&] { reader->readScan(4); }, scan(4).string(), "truncated PNG");
}

TEST_F(OxfordCopy, CorruptPngIsAnError) {
  const auto file = scan(2);
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(std::filesystem::file_size(file) / 2));
    f.write("garbage!", 8);
  }
  const auto reader = openDataset(root_);
  ::testing::internal::CaptureStderr();
  expectInputError([&] { reader->readScan(2); }, file.string(), "corrupt PNG");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  test::writeText(scan(5), "this is not an image");
  expectInputError([&] { reader->readScan(5); }, scan(5).string(), "not a PNG");
  std::filesystem::remove(scan(6));
  expectInputError([&] { reader->readScan(6); }, "radar/", "cannot open file");
}

TEST_F(OxfordCopy, WrongImageSizeIsAnError) {
  const cv::Mat img = cv::imread(scan(0).string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(img.cols, 3779);
  const auto narrow = scan(5), short_ = scan(6);
  ASSERT_TRUE(cv::imwrite(narrow.string(), img.colRange(0, 3000).clone()));
  ASSERT_TRUE(cv::imwrite(short_.string(), img.rowRange(0, 200).clone()));
  const auto reader = openDataset(root_);
  EXPECT_NO_THROW(reader->readScan(4));
  expectInputError([&] { reader->readScan(5); }, narrow.string(),
                   "image is 3000x400 (WxH) but this sequence's scans are 3779x400");
  expectInputError([&] { reader->readScan(6); }, short_.string(), "3779x200");
  // A standalone image too narrow for the Oxford layout.
  ASSERT_TRUE(cv::imwrite(scan(0).string(), img.colRange(0, 8).clone()));
  expectInputError([&] { readScanFile(scan(0)); }, scan(0).string(), "metadata columns");
}

TEST_F(OxfordCopy, ScanIteratorSkipsBadScansOnlyWhenAsked) {
  std::filesystem::resize_file(scan(3), 1000);
  const auto reader = openDataset(root_);
  {
    ScanIterator it(*reader, /*skip_bad_scans=*/true);
    std::vector<std::size_t> seen;
    while (auto s = it.next()) seen.push_back(it.index());
    EXPECT_EQ(seen, (std::vector<std::size_t>{0, 1, 2, 4, 5, 6, 7, 8, 9, 10}));
    EXPECT_EQ(it.skipped(), 1u);
    EXPECT_EQ(it.total(), 11u);
  }
  ScanIterator strict(*reader, false, 1, 5);
  EXPECT_EQ(strict.total(), 4u);
  EXPECT_TRUE(strict.next());
  EXPECT_TRUE(strict.next());
  expectInputError([&] { strict.next(); }, scan(3).string(), "truncated PNG");
}

TEST_F(OxfordCopy, ScanFileHoldingAnotherScanIsSkipped) {
  // Swap two scan files' content: scan 5's file now holds scan 4's data (an earlier sweep).
  std::filesystem::copy_file(scan(4), scan(5), std::filesystem::copy_options::overwrite_existing);
  const auto reader = openDataset(root_);
  expectInputError([&] { reader->readScan(5); }, scan(5).string(), "differs from the file's timestamp");
  ScanIterator it(*reader, true);
  std::size_t n = 0;
  while (it.next()) ++n;
  EXPECT_EQ(n, 10u);
  EXPECT_EQ(it.skipped(), 1u);
}

TEST_F(OxfordCopy, MissingOrNonMonotonicTimestampsAreErrors) {
  const auto ts = root_ / "radar.timestamps";
  const std::string text = test::readText(ts);
  std::filesystem::remove(ts);
  expectInputError([&] { openDataset(root_); }, "radar.timestamps", "missing radar.timestamps");
  // Line 5 set to an earlier time than line 4.
  test::writeText(ts, replaceLine(text, 4, "1547131046606586 1"));
  expectInputError([&] { openDataset(root_); }, "radar.timestamps:5", "not increasing");
  test::writeText(ts, replaceLine(text, 2, "15471310468x8560 1"));
  expectInputError([&] { openDataset(root_); }, "radar.timestamps:3", "timestamp is not an integer");
}

TEST_F(OxfordCopy, GroundTruthGapsAndMalformedRowsAreErrors) {
  const auto gt = root_ / "gt" / "radar_odometry.csv";
  const std::string text = test::readText(gt);
  // Drop the row on line 101: line 101 of the new file no longer continues line 100.
  std::string without;
  {
    std::istringstream in(text);
    std::string line;
    for (std::size_t i = 1; std::getline(in, line); ++i)
      if (i != 101) without.append(line).append("\n");
  }
  test::writeText(gt, without);
  expectInputError([&] { openDataset(root_); }, "radar_odometry.csv:101", "ground-truth gap");
  test::writeText(gt, replaceLine(text, 6, "1547131015235031,1547131014983426,0.000985,0.000290"));
  expectInputError([&] { openDataset(root_); }, "radar_odometry.csv:7",
                   "expected 10 comma-separated fields, got 4");
  test::writeText(gt, replaceLine(text, 6, "1547131016245070,1547131015992442,abc,0,0,0,0,0,1,2"));
  expectInputError([&] { openDataset(root_); }, "radar_odometry.csv:7", "x is not a finite number: 'abc'");
  test::writeText(gt, "time,x,y\n1,2,3\n");
  expectInputError([&] { openDataset(root_); }, "radar_odometry.csv", "unexpected header");
}

TEST(DatasetDetection, UnknownLayoutAndEmptyDirectoryAreErrors) {
  test::TempDir tmp;
  expectInputError([&] { openDataset(tmp.path()); }, tmp.path().string(), "empty directory");
  test::writeText(tmp / "notes.txt", "hello");
  expectInputError([&] { openDataset(tmp.path()); }, tmp.path().string(), "unknown dataset layout");
  expectInputError([&] { openDataset(tmp / "missing"); }, "missing", "no such file or directory");
  expectInputError([&] { openDataset(tmp / "notes.txt"); }, "notes.txt", "unknown dataset layout");
  std::filesystem::create_directories(tmp / "radar");
  expectInputError([&] { openDataset(tmp.path()); }, "radar.timestamps", "missing radar.timestamps");
  expectInputError([&] { readScanFile(tmp / "notes.txt"); }, "notes.txt", "unknown scan file type");
  test::writeTransposedPng(tmp / "elsewhere" / "1.png", 4, 4);
  expectInputError([&] { readScanFile(tmp / "elsewhere" / "1.png"); }, "1.png", "cannot tell the dataset");
}
