// The real program on hostile input (issue 15): maps whose checksums are valid but whose content
// is not (NaN poses, dangling edges, zero resolution), FIFOs and directories where map or scan
// files should be, and a dataset path that is not UTF-8. Every run is bounded by `timeout 20`:
// a FIFO that blocks open() shows up as exit 124 instead of a hung test.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>

#include "../map/synthetic_map.h"
#include "cli_run.h"
#include "radarslam/io/oxford_writer.h"
#include "radarslam/map/map_io.h"
#include "radarslam/obs/registration.h"
#include "synthetic_oxford.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using radarslam::KeyframeMap;

using CliRun = radarslam::test::CliResult;

// `timeout 20 radarslam ARGS` (ARGS shell-quoted by the caller).
CliRun radarslamRun(const std::string& args, const fs::path& dir) {
  return radarslam::test::runCommand("timeout 20 " + std::string(RADARSLAM_CLI) + " " + args, dir);
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// Exit 1 and exactly one line "radarslam: error: ..." containing every needle.
void expectOneLineError(const CliRun& r, std::initializer_list<std::string> needles) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("radarslam: error: ", 0), 0u) << r.err;
  for (const auto& n : needles)
    EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' not in " << r.err;
}

class HostileMap : public ::testing::Test {
 protected:
  // A 4-scan Oxford-layout dataset (with ground truth), written once for the suite.
  static void SetUpTestSuite() {
    radarslam::registerRadarslamClasses();
    root_ = new fs::path(fs::temp_directory_path() / ("radarslam_cli_hostile_" + std::to_string(::getpid())));
    fs::create_directories(*root_);
    radarslam::test::writeNoiseOxfordDataset(*root_ / "ds", 4, 5);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*root_, ec);
    delete root_;
  }
  static fs::path dataset() { return *root_ / "ds"; }
  // A copy of the dataset in this test's directory (to break one of its files).
  fs::path datasetCopy() const {
    const fs::path copy = tmp_ / "ds";
    fs::copy(dataset(), copy, fs::copy_options::recursive);
    return copy;
  }
  fs::path badMap(const std::function<void(KeyframeMap&)>& corrupt) const {
    KeyframeMap map = radarslam::test::syntheticMap(4, 20);
    corrupt(map);
    const fs::path dir = tmp_ / "bad";
    radarslam::saveMap(map, dir);  // valid checksums of invalid content
    return dir;
  }
  // export, localize and map --extend on `map`: each one line naming `file` and `problem`.
  void expectEveryCommandRefuses(const fs::path& map, const std::string& file, const std::string& problem) {
    expectOneLineError(radarslamRun("export " + q(map), tmp_.path()), {file, problem});
    expectOneLineError(
        radarslamRun("localize " + q(map) + " " + q(dataset()) + " -o " + q(tmp_ / "p.tum") + " -q",
                     tmp_.path()),
        {file, problem});
    expectOneLineError(radarslamRun("map " + q(dataset()) + " --extend " + q(map) + " -o " + q(tmp_ / "out") +
                                        " --threads 1 -q",
                                    tmp_.path()),
                       {file, problem});
    EXPECT_FALSE(fs::exists(tmp_ / "p.tum"));
    EXPECT_FALSE(fs::exists(tmp_ / "out"));
  }
  static fs::path* root_;
  radarslam::test::TempDir tmp_;
};
fs::path* HostileMap::root_ = nullptr;

TEST_F(HostileMap, NanPoseWithValidChecksumsIsRefusedByEveryCommand) {
  const auto map =
      badMap([](KeyframeMap& m) { m.keyframes[2].pose.x = std::numeric_limits<double>::quiet_NaN(); });
  expectEveryCommandRefuses(map, "keyframes.bin", "keyframe 12: pose x is NaN");
}

TEST_F(HostileMap, DanglingEdgeIsRefused) {
  const auto map = badMap([](KeyframeMap& m) { m.edges[0].from = 4242; });
  expectOneLineError(radarslamRun("export " + q(map), tmp_.path()), {"graph.bin", "keyframe 4242"});
}

TEST_F(HostileMap, ZeroResolutionIsRefused) {
  const auto map = badMap([](KeyframeMap& m) { m.meta.sensor.range_resolution_m = 0; });
  expectEveryCommandRefuses(map, "manifest.yaml", "range_resolution_m must be > 0");
}

TEST_F(HostileMap, FifoInPlaceOfAMapFileDoesNotHang) {
  const auto map = badMap([](KeyframeMap&) {});
  fs::remove(map / "points.bin");
  ASSERT_EQ(::mkfifo((map / "points.bin").c_str(), 0600), 0);
  expectOneLineError(radarslamRun("export " + q(map), tmp_.path()),
                     {"points.bin", "not a regular file (a FIFO)"});
  fs::remove(map / "manifest.yaml");
  ASSERT_EQ(::mkfifo((map / "manifest.yaml").c_str(), 0600), 0);
  expectOneLineError(radarslamRun("export " + q(map), tmp_.path()), {"manifest.yaml", "not a regular file"});
}

// A scan that cannot be read stops the run: exit 1, the last line of stderr is the one error line
// (after the command's status line), and no other line is an error.
void expectScanError(const CliRun& r, std::initializer_list<std::string> needles) {
  EXPECT_EQ(r.code, 1) << r.err;
  ASSERT_FALSE(r.err.empty());
  const auto start = r.err.rfind('\n', r.err.size() - 2);
  const std::string last = r.err.substr(start == std::string::npos ? 0 : start + 1);
  EXPECT_EQ(last.rfind("radarslam: error: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("error:"), r.err.rfind("error:")) << r.err;
  for (const auto& n : needles)
    EXPECT_NE(last.find(n), std::string::npos) << "'" << n << "' not in " << r.err;
}

TEST_F(HostileMap, FifoInPlaceOfAScanFileDoesNotHang) {
  const fs::path ds = datasetCopy();
  fs::path scan;
  for (const auto& e : fs::directory_iterator(ds / "radar")) scan = std::max(scan, e.path());  // the last one
  fs::remove(scan);
  ASSERT_EQ(::mkfifo(scan.c_str(), 0600), 0);
  expectScanError(radarslamRun("odometry " + q(ds) + " -o " + q(tmp_ / "t.tum") + " -q", tmp_.path()),
                  {scan.filename().string(), "not a regular file (a FIFO)"});
}

TEST_F(HostileMap, DirectoryInPlaceOfAScanFileIsOneLine) {
  const fs::path ds = datasetCopy();
  fs::path scan;
  for (const auto& e : fs::directory_iterator(ds / "radar")) scan = std::max(scan, e.path());
  fs::remove(scan);
  fs::create_directory(scan);
  expectScanError(radarslamRun("odometry " + q(ds) + " -o " + q(tmp_ / "t.tum") + " -q", tmp_.path()),
                  {scan.filename().string(), "not a regular file (a directory)"});
}

TEST_F(HostileMap, NonUtf8DatasetPathMakesALoadableMap) {
  // Not UTF-8, a newline, quotes, ": " and "#": all written into the manifest's source_dataset.
  const fs::path odd = tmp_ / std::string("d\xff\xfe \"x\": #y\nz");
  fs::copy(dataset(), odd, fs::copy_options::recursive);
  const fs::path map = tmp_ / "m";
  CliRun r = radarslamRun("map-synth " + q(odd) + " -o " + q(map), tmp_.path());
  ASSERT_EQ(r.code, 0) << r.err;
  r = radarslamRun("export " + q(map) + " -o " + q(tmp_ / "exports"), tmp_.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(radarslam::loadMap(map).meta.source_dataset.find("d\xff\xfe \"x\": #y\nz"), std::string::npos);
}

}  // namespace
