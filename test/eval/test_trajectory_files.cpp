// TUM / KITTI trajectory files (io/trajectory_files.h): round trips, stamps, and one-line errors
// that name the file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "file_contents.h"
#include "radarslam/core/errors.h"
#include "radarslam/io/trajectory_files.h"
#include "synthetic.h"
#include "temp_dir.h"

using namespace radarslam;
using mrpt::math::TPose2D;

namespace {

using radarslam::test::writeFileBytes;

/// Runs `f`, expects an InputError and returns it.
template <typename F>
InputError expectInputError(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError thrown";
  return InputError("", "");
}

Trajectory realisticTrajectory() {
  Trajectory t = test::windingDrive(200);
  for (std::size_t k = 0; k < t.size(); ++k)  // Oxford-like epoch stamps with odd nanoseconds
    t[k].stamp = 1547120788016733123LL + static_cast<StampNs>(k) * 249'876'543LL;
  return t;
}

void expectSamePoses(const Trajectory& a, const Trajectory& b, double tol_m, double tol_rad) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].stamp, b[i].stamp) << i;
    ASSERT_NEAR(a[i].pose.x, b[i].pose.x, tol_m) << i;
    ASSERT_NEAR(a[i].pose.y, b[i].pose.y, tol_m) << i;
    ASSERT_NEAR(std::remainder(a[i].pose.phi - b[i].pose.phi, 2 * std::numbers::pi), 0.0, tol_rad) << i;
  }
}
}  // namespace

TEST(StampText, ParsesDecimalSecondsExactlyAndIntegersByDigits) {
  StampNs t = 0;
  ASSERT_TRUE(parseStampText("1547120788.016733", t));
  EXPECT_EQ(t, 1547120788016733000LL);
  ASSERT_TRUE(parseStampText("1547120788.0167331239", t));  // beyond ns: truncated
  EXPECT_EQ(t, 1547120788016733123LL);
  ASSERT_TRUE(parseStampText("1547120788016733", t));  // 16 digits: microseconds
  EXPECT_EQ(t, 1547120788016733000LL);
  ASSERT_TRUE(parseStampText("1.036000e-01", t));  // KITTI times.txt
  EXPECT_EQ(t, 103600000);
  ASSERT_TRUE(parseStampText("-2.5", t));
  EXPECT_EQ(t, -2500000000LL);
  for (const char* bad : {"", ".", "abc", "1.2.3", "12a.5", "1e", "nan"})
    EXPECT_FALSE(parseStampText(bad, t)) << bad;
  EXPECT_EQ(formatStampSeconds(1547120788016733123LL), "1547120788.016733123");
  EXPECT_EQ(formatStampSeconds(-2500000000LL), "-2.500000000");
}

TEST(TrajectoryFiles, TumRoundTripKeepsNanosecondStamps) {
  test::TempDir dir;
  const Trajectory t = realisticTrajectory();
  writeTumTrajectory(dir / "sub/est.txt", t);  // creates the directory
  EXPECT_EQ(detectTrajectoryFormat(dir / "sub/est.txt"), TrajectoryFormat::Tum);
  expectSamePoses(readTrajectoryFile(dir / "sub/est.txt"), t, 1e-6, 1e-8);
}

TEST(TrajectoryFiles, KittiRoundTripUsesTheStampsCompanion) {
  test::TempDir dir;
  const Trajectory t = realisticTrajectory();
  writeKittiTrajectory(dir / "est.txt", t);
  ASSERT_TRUE(std::filesystem::exists(dir / "est.times.txt"));
  EXPECT_EQ(kittiStampsCompanion(dir / "est.txt"), dir / "est.times.txt");
  EXPECT_EQ(detectTrajectoryFormat(dir / "est.txt"), TrajectoryFormat::Kitti);
  expectSamePoses(readTrajectoryFile(dir / "est.txt"), t, 1e-6, 1e-8);
}

TEST(TrajectoryFiles, KittiWithoutStampsUsesTheIndexOrAGivenStampFile) {
  test::TempDir dir;
  writeFileBytes(dir / "poses.txt",
                 "1 0 0 0 0 1 0 0 0 0 1 0\n"
                 "0 -1 0 2.5 1 0 0 1 0 0 1 0\n"
                 "1.000000e+00 0.000000e+00 0.000000e+00 5.0e+00 0 1 0 2 0 0 1 0.3\n");
  const Trajectory t = readKittiTrajectory(dir / "poses.txt");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[2].stamp, 2 * kNsPerSec);
  EXPECT_DOUBLE_EQ(t[1].pose.x, 2.5);
  EXPECT_DOUBLE_EQ(t[1].pose.y, 1.0);
  EXPECT_NEAR(t[1].pose.phi, std::numbers::pi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(t[2].pose.x, 5.0);

  writeFileBytes(dir / "times.txt", "0.000000e+00\n1.036000e-01\n2.071000e-01\n");
  TrajectoryReadOptions options;
  options.stamps_file = dir / "times.txt";
  const Trajectory s = readTrajectoryFile(dir / "poses.txt", options);
  EXPECT_EQ(s[1].stamp, 103600000);
  EXPECT_EQ(s[2].stamp, 207100000);

  writeFileBytes(dir / "short.txt", "0\n");
  options.stamps_file = dir / "short.txt";
  const InputError e = expectInputError([&] { readTrajectoryFile(dir / "poses.txt", options); });
  EXPECT_EQ(e.where(), (dir / "poses.txt").string() + ":2");
}

TEST(TrajectoryFiles, ReadsStampedKittiAndSkipsComments) {
  test::TempDir dir;
  writeFileBytes(dir / "boreas.txt",
                 "# pyboreas style: stamp then 3x4\n\n"
                 "1632182400000000 1 0 0 10 0 1 0 20 0 0 1 0\n"
                 "1632182400250000 1 0 0 11 0 1 0 20 0 0 1 0\n");
  const Trajectory t = readTrajectoryFile(dir / "boreas.txt");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1].stamp, 1632182400250000000LL);
  EXPECT_DOUBLE_EQ(t[1].pose.x, 11.0);
  EXPECT_THROW(readKittiTrajectory(dir / "boreas.txt", {1, 2}), InputError);  // two sources of stamps
}

TEST(TrajectoryFiles, TumYawComesFromTheQuaternion) {
  test::TempDir dir;
  const double yaw = 2.5;
  writeFileBytes(dir / "q.txt", "10.5 1 2 3 0 0 " + std::to_string(std::sin(yaw / 2)) + " " +
                                    std::to_string(std::cos(yaw / 2)) + "\n");
  const Trajectory t = readTumTrajectory(dir / "q.txt");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].stamp, 10'500'000'000LL);
  EXPECT_NEAR(t[0].pose.phi, yaw, 1e-6);
}

TEST(TrajectoryFiles, BadLinesNameTheFileAndLine) {
  test::TempDir dir;
  const auto f = dir / "bad.txt";
  const std::string good = "1.0 0 0 0 0 0 0 1\n";
  struct Case {
    std::string text;
    std::string line;
    std::string words;
  };
  const std::vector<Case> cases{
      {"# header\n" + good + "2.0 0 0 0 0 0 1\n", ":3", "expected 8 numbers"},
      {good + "2.0 nan 0 0 0 0 0 1\n", ":2", "not finite"},
      {good + "2.0 1 x 0 0 0 0 1\n", ":2", "cannot parse y"},
      {good + "1.0 1 0 0 0 0 0 1\n", ":2", "does not increase"},
      {good + "0.5 1 0 0 0 0 0 1\n", ":2", "does not increase"},
      {good + "2.0 1 0 0 0 0 0 2\n", ":2", "norm"},
      {good + "2.0e 1 0 0 0 0 0 1\n", ":2", "timestamp"},
  };
  for (const auto& c : cases) {
    writeFileBytes(f, c.text);
    const InputError e = expectInputError([&] { readTrajectoryFile(f, {TrajectoryFormat::Tum, {}}); });
    EXPECT_EQ(e.where(), f.string() + c.line) << c.text;
    EXPECT_NE(e.problem().find(c.words), std::string::npos) << e.what();
  }
  writeFileBytes(f, "1 0 0 0 0 1 0 0 0 0 1 0\n2 0 0 0 0 1 0 0 0 0 1 0\n");
  const InputError not_rotation = expectInputError([&] { readKittiTrajectory(f); });
  EXPECT_EQ(not_rotation.where(), f.string() + ":2");
  writeFileBytes(f, "1 2 3\n");
  EXPECT_EQ(expectInputError([&] { readTrajectoryFile(f); }).where(), f.string() + ":1");
  writeFileBytes(f, "# nothing\n");
  EXPECT_EQ(expectInputError([&] { readTrajectoryFile(f); }).where(), f.string());
  EXPECT_NE(std::string(expectInputError([&] { readTrajectoryFile(dir / "missing.txt"); }).what())
                .find("not found"),
            std::string::npos);
  EXPECT_THROW(parseTrajectoryFormat("csv", "--est-format"), InputError);
  EXPECT_EQ(parseTrajectoryFormat("KITTI", "x"), TrajectoryFormat::Kitti);
}
