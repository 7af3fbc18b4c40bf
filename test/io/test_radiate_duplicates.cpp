// RADIATE Navtech_Polar.txt listing a frame twice: the same line repeated is read once (one
// warning with the count); the same frame number with another time is an error naming the line.
#include <gtest/gtest.h>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "temp_dir.h"

using namespace radarslam;

namespace {

void writeRadiate(const std::filesystem::path& root, const std::string& times) {
  for (const char* f : {"000001", "000002", "000003"})
    test::writeTransposedPng(root / "Navtech_Polar" / (std::string(f) + ".png"), 40, 30);
  test::writeText(root / "Navtech_Polar.txt", times);
}

}  // namespace

TEST(RadiateDuplicates, RepeatedFrameLinesAreReadOnceWithOneWarning) {
  test::TempDir tmp;
  writeRadiate(tmp.path(),
               "Frame: 000001 Time: 1574859771.744660272\n"
               "Frame: 000002 Time: 1574859771.994660272\n"
               "Frame: 000002 Time: 1574859771.994660272\n"
               "Frame: 000003 Time: 1574859772.244660272\n"
               "Frame: 000002 Time: 1574859771.994660272\n");
  ::testing::internal::CaptureStderr();
  const auto reader = openDataset(tmp.path());
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(reader->size(), 3u);
  EXPECT_NE(err.find("Navtech_Polar.txt: 2 duplicate frame line(s) skipped"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  for (std::size_t i = 0; i < reader->size(); ++i)
    EXPECT_EQ(reader->scanPath(i).filename(), "00000" + std::to_string(i + 1) + ".png");
}

TEST(RadiateDuplicates, AFrameListedWithTwoTimesIsAnError) {
  test::TempDir tmp;
  writeRadiate(tmp.path(),
               "Frame: 000001 Time: 1574859771.744660272\n"
               "Frame: 000002 Time: 1574859771.994660272\n"
               "Frame: 000002 Time: 1574859772.244660272\n");
  try {
    openDataset(tmp.path());
    ADD_FAILURE() << "frame 000002 with two times was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Navtech_Polar.txt:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("frame 000002 listed again with a different time"),
              std::string::npos)
        << e.what();
  }
}
