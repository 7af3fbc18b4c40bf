// `radarslam cart` end to end on the real Oxford tiny sample: image size, the --peaks overlay,
// and one-line errors with a non-zero exit code for bad arguments.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "file_contents.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace {

struct Result {
  int code = -1;
  std::string err;
};

Result runCli(const std::string& args, const radarslam::test::TempDir& tmp) {
  const auto err_file = tmp / "stderr.txt";
  const std::string cmd =
      std::string(RADARSLAM_CLI) + " " + args + " 2> '" + err_file.string() + "' > /dev/null";
  const int status = std::system(cmd.c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = radarslam::test::readFileBytes(err_file);
  return r;
}

// Width, height and colour type from the PNG IHDR chunk (bytes 16..25).
struct PngInfo {
  unsigned width = 0, height = 0, color_type = 99;
};
PngInfo pngInfo(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[26] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  EXPECT_TRUE(in.good()) << path;
  EXPECT_EQ(std::string(reinterpret_cast<char*>(h + 1), 3), "PNG");
  auto be32 = [&](int o) {
    return (unsigned(h[o]) << 24) | (unsigned(h[o + 1]) << 16) | (unsigned(h[o + 2]) << 8) | h[o + 3];
  };
  return {be32(16), be32(20), h[25]};
}

std::size_t lineCount(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(CliCart, WritesTheCartesianImage) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const auto out = tmp / "scan.png";
  Result r =
      runCli("cart '" + dir.string() + "' '" + out.string() + "' --index 3 --size 401 --resolution 0.5", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  PngInfo info = pngInfo(out);
  EXPECT_EQ(info.width, 401u);
  EXPECT_EQ(info.height, 401u);
  EXPECT_EQ(info.color_type, 0u);  // greyscale

  // A single scan file, default size, with the peak overlay (colour).
  const auto first_scan = dir / "radar" / "1547131046353776.png";
  const auto out2 = tmp / "sub" / "peaks.png";
  r = runCli("cart '" + first_scan.string() + "' '" + out2.string() + "' --peaks", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  info = pngInfo(out2);
  EXPECT_EQ(info.width, 701u);
  EXPECT_EQ(info.height, 701u);
  EXPECT_EQ(info.color_type, 2u);  // RGB
}

TEST(CliCart, ReadsAScanFromARawlog) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const auto rawlog = tmp / "two.rawlog";
  Result r = runCli("convert '" + dir.string() + "' '" + rawlog.string() + "' --first 4 --count 2", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto out = tmp / "from_rawlog.png";
  r = runCli("cart '" + rawlog.string() + "' '" + out.string() + "' --index 1 --size 300", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(pngInfo(out).width, 300u);
  r = runCli("cart '" + rawlog.string() + "' '" + out.string() + "' --index 2", tmp);  // only 2 scans
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("out of range"), std::string::npos) << r.err;
}

TEST(CliCart, BadArgumentsFailWithOneLine) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  radarslam::test::TempDir tmp;
  const std::string out = "'" + (tmp / "x.png").string() + "'";
  const std::string ds = "'" + dir.string() + "'";
  for (const std::string& args : std::vector<std::string>{
           "cart", "cart " + ds, "cart " + ds + " " + out + " --size 0",
           "cart " + ds + " " + out + " --resolution -1", "cart " + ds + " " + out + " --index 99999",
           "cart " + ds + " " + out + " --bogus", "cart /nonexistent/dir " + out,
           "cart " + ds + " '" + (tmp / "x.jpg").string() + "'", "cart " + ds + " " + out + " --size abc"}) {
    const Result r = runCli(args, tmp);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << args << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(tmp / "x.png"));
}

TEST(CliCart, Help) {
  radarslam::test::TempDir tmp;
  const Result r = runCli("cart --help", tmp);
  EXPECT_EQ(r.code, 0);
}

}  // namespace
