// radarslam-map-server when the map on disk is replaced by a bad one (valid checksums, NaN pose):
// it keeps publishing the last good map, says so once (not on every poll), stays responsive to
// SIGTERM, and picks up the next good map when the files change again.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <limits>

#include <radarslam/dds/map_messages.h>
#include <radarslam/map/map_io.h>

#include "dds_test_util.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using test::Child;

std::string gridSha(const KeyframeMap& map) {
  GridExportParams p;
  p.resolution_m = 0.2;
  return dds::gridSha256(dds::gridMessage(map, p, 0));
}

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + 1)) ++n;
  return n;
}

std::vector<std::string> clientArgs(const fs::path& out, unsigned domain, const std::string& expect_sha) {
  return {RADARSLAM_MAP_CLIENT,
          "-o",
          out.string(),
          "--domain",
          std::to_string(domain),
          "--timeout",
          "15",
          "--layers",
          "grid",
          "--expect-grid-sha256",
          expect_sha};
}

TEST(MapServerBadReload, KeepsTheLastGoodMapAndLogsTheFailureOnce) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "site";
  const KeyframeMap good = test::syntheticMap(4, 200, 30.0, 21);
  saveMap(good, map_dir);
  const unsigned dom = test::testDomainId(18);
  Child server({RADARSLAM_MAP_SERVER, "--map", map_dir.string(), "--domain", std::to_string(dom), "--layers",
                "grid", "--poll", "0.05"},
               tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("revision 1", 15)) << server.err();

  KeyframeMap bad = test::syntheticMap(5, 200, 30.0, 22);
  bad.keyframes[1].pose.x = std::numeric_limits<double>::quiet_NaN();
  saveMap(bad, map_dir);  // atomically swapped in, checksums valid
  ASSERT_TRUE(server.waitForLog("keeping revision 1", 15)) << server.err();
  std::this_thread::sleep_for(std::chrono::milliseconds(600));  // > 10 polls of the unchanged bad map
  const std::string log = server.err();
  EXPECT_EQ(count(log, "keeping revision 1"), 1u) << log;
  EXPECT_EQ(count(log, "changed on disk, reloading"), 1u) << log;
  EXPECT_NE(log.find("keyframe 1: pose x is NaN"), std::string::npos) << log;

  // A client joining now gets the old, good map.
  {
    Child client(clientArgs(tmp.path() / "a", dom, gridSha(good)), tmp.path() / "client_a");
    EXPECT_EQ(client.wait(20), 0) << client.err();
    EXPECT_NE(test::readText(tmp.path() / "a" / "map_info.yaml").find("revision: 1"), std::string::npos);
  }
  // The next good map (the files change) is loaded.
  const KeyframeMap next = test::syntheticMap(5, 250, 35.0, 23);
  saveMap(next, map_dir);
  ASSERT_TRUE(server.waitForLog("revision 2", 15)) << server.err();
  {
    Child client(clientArgs(tmp.path() / "b", dom, gridSha(next)), tmp.path() / "client_b");
    EXPECT_EQ(client.wait(20), 0) << client.err();
  }
  server.signal(SIGTERM);
  EXPECT_EQ(server.wait(10), 0) << server.err();
}

TEST(MapServerBadReload, AFifoInPlaceOfAMapFileDoesNotBlockTheServer) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "site";
  saveMap(test::syntheticMap(3, 100, 20.0, 24), map_dir);
  Child server({RADARSLAM_MAP_SERVER, "--map", map_dir.string(), "--domain",
                std::to_string(test::testDomainId(19)), "--layers", "grid", "--poll", "0.05"},
               tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("revision 1", 15)) << server.err();
  fs::remove(map_dir / "points.bin");
  ASSERT_EQ(::mkfifo((map_dir / "points.bin").c_str(), 0600), 0);
  std::ofstream(map_dir / "manifest.yaml", std::ios::app) << "# edited\n";  // the manifest changed
  ASSERT_TRUE(server.waitForLog("not a regular file (a FIFO)", 15)) << server.err();
  server.signal(SIGTERM);  // not stuck in open()
  EXPECT_EQ(server.wait(10), 0) << server.err();
}

}  // namespace
}  // namespace radarslam
