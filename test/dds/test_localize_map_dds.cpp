// `radarslam localize dds: ...` with real processes on loopback (docs/dds.md, "The map files
// layer"): radarslam-map-server publishes the map's files on rt/radarslam/map_files, the localiser
// receives them into a private temporary directory and must produce exactly the poses it produces
// from the map directory; it removes that directory, fails with one line after --map-timeout when
// no map arrives, and follows the server's reloads (newest revision).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <radarslam/map/map_io.h>

#include "dds_test_util.h"
#include "simulated_dataset.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;

/// Runs `radarslam ARGS` to completion; returns the exit code (stdout/stderr in `log`.out/.err).
int runCli(const std::vector<std::string>& args, const fs::path& log, double timeout_s = 60) {
  std::vector<std::string> all{RADARSLAM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  test::Child c(all, log);
  return c.wait(timeout_s);
}

/// A domain no test server publishes map files on (testDomainId covers 1..200; Cyclone < 233).
unsigned quietDomainId() { return 201 + static_cast<unsigned>(::getpid()) % 32; }

/// Points TMPDIR (where the localiser makes its private directory) at a fresh directory for the
/// children started while it lives.
struct PrivateTmpdir {
  fs::path dir;
  std::string old;
  bool had_old;
  explicit PrivateTmpdir(const fs::path& d) : dir(d) {
    fs::create_directories(dir);
    const char* o = std::getenv("TMPDIR");
    had_old = o != nullptr;
    if (o) old = o;
    ::setenv("TMPDIR", dir.c_str(), 1);
  }
  ~PrivateTmpdir() { had_old ? ::setenv("TMPDIR", old.c_str(), 1) : ::unsetenv("TMPDIR"); }
  bool empty() const { return fs::is_empty(dir); }
};

TEST(LocalizeMapDds, PosesEqualTheOnesFromTheMapDirectoryAndFollowReloads) {
  test::TempDir tmp;
  const fs::path data = test::simulatedDataset("--scans 40"), map = tmp / "map";  // shared, read only
  ASSERT_EQ(runCli({"map-synth", data.string(), "-o", map.string()}, tmp / "synth"), 0)
      << test::readText(tmp / "synth.err");
  const unsigned dom = test::testDomainId(16);
  // 64 KiB chunks: keyframes.bin (~270 kB) takes several, as a real map's files do with 4 MiB.
  test::Child server({RADARSLAM_MAP_SERVER, "--map", map.string(), "--domain", std::to_string(dom),
                      "--files-chunk-bytes", "65536", "--poll", "0.1"},
                     tmp / "server");
  ASSERT_TRUE(server.waitForLog("published map", 20)) << server.err();
  EXPECT_NE(server.err().find("files 5 ("), std::string::npos) << server.err();

  PrivateTmpdir private_tmp(tmp / "tmpdir");
  const fs::path from_dds = tmp / "dds.tum", from_dir = tmp / "dir.tum";
  ASSERT_EQ(runCli({"localize", "dds:" + std::to_string(dom), data.string(), "-o", from_dds.string(), "-q"},
                   tmp / "loc_dds"),
            0)
      << test::readText(tmp / "loc_dds.err");
  ASSERT_EQ(runCli({"localize", map.string(), data.string(), "-o", from_dir.string(), "-q"}, tmp / "loc_dir"),
            0)
      << test::readText(tmp / "loc_dir.err");
  const std::string poses = test::readText(from_dds);
  EXPECT_GT(std::count(poses.begin(), poses.end(), '\n'), 30);
  EXPECT_EQ(poses, test::readText(from_dir));  // byte-equal TUM
  EXPECT_NE(test::readText(tmp / "loc_dds.err").find("received map 'map' revision 1: 5 files"),
            std::string::npos)
      << test::readText(tmp / "loc_dds.err");
  EXPECT_TRUE(private_tmp.empty()) << "the localiser left its temporary directory behind";

  // The map changes on disk: the server publishes revision 2, a new localiser gets that one.
  ASSERT_EQ(runCli({"map-synth", data.string(), "-o", map.string(), "--max-keyframes", "8"}, tmp / "synth2"),
            0)
      << test::readText(tmp / "synth2.err");
  ASSERT_TRUE(server.waitForLog("revision 2", 20)) << server.err();
  ASSERT_EQ(runCli({"localize", "dds:", "dds:", "--domain", std::to_string(dom), "-o",
                    (tmp / "r2.tum").string(), "-q", "--dds-timeout", "0.5"},
                   tmp / "loc_r2"),
            1);  // no scans on DDS: exits 1 after receiving and loading the map
  EXPECT_NE(test::readText(tmp / "loc_r2.err").find("received map 'map' revision 2"), std::string::npos)
      << test::readText(tmp / "loc_r2.err");
  EXPECT_TRUE(private_tmp.empty());
  server.signal(SIGTERM);
  EXPECT_EQ(server.wait(10), 0);
}

TEST(LocalizeMapDds, NoMapIsAOneLineErrorAfterTheMapTimeout) {
  test::TempDir tmp;
  PrivateTmpdir private_tmp(tmp / "tmpdir");
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(runCli({"localize", "dds:" + std::to_string(quietDomainId()), "dds:", "-o",
                    (tmp / "x.tum").string(), "--map-timeout", "1", "-q"},
                   tmp / "loc"),
            1);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(s, 1.0);
  EXPECT_LT(s, 15.0 * test::timeScale());
  const std::string err = test::readText(tmp / "loc.err");
  EXPECT_EQ(err,
            "radarslam: error: dds:" + std::to_string(quietDomainId()) +
                ": no map on rt/radarslam/map_files within 1 s (is radarslam-map-server running on domain " +
                std::to_string(quietDomainId()) + "?)\n");
  EXPECT_FALSE(fs::exists(tmp / "x.tum"));
  EXPECT_TRUE(private_tmp.empty());
  // A MAP that starts with dds: but names no domain.
  EXPECT_EQ(runCli({"localize", "dds:x", "dds:", "-o", (tmp / "x.tum").string()}, tmp / "bad"), 1);
  EXPECT_NE(test::readText(tmp / "bad.err").find("dds:x: expected dds: or dds:DOMAIN"), std::string::npos)
      << test::readText(tmp / "bad.err");
}

TEST(LocalizeMapDds, ServerRefusesAMapFileThatFailsItsChecksum) {
  test::TempDir tmp;
  const fs::path map = tmp / "map";
  saveMap(test::syntheticMap(4, 200, 30.0, 7), map);
  std::string bytes = test::readText(map / "points.bin");
  bytes[0] ^= 0x01;  // same size, other content
  std::ofstream(map / "points.bin", std::ios::binary | std::ios::trunc) << bytes;
  test::Child server({RADARSLAM_MAP_SERVER, "--map", map.string(), "--domain",
                      std::to_string(quietDomainId()), "--layers", "files"},
                     tmp / "server");
  EXPECT_EQ(server.wait(20), 1);
  EXPECT_NE(server.err().find("points.bin: checksum mismatch"), std::string::npos) << server.err();
}

}  // namespace
}  // namespace radarslam
