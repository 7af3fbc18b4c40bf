// radarslam-map-server and radarslam-map-client as real separate processes on loopback, each test
// on its own DDS domain.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <radarslam/dds/map_messages.h>
#include <radarslam/map/map_io.h>
#include <radarslam/map/sha256.h>

#include "dds_test_util.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using test::Child;

const std::string kServer = RADARSLAM_MAP_SERVER;
const std::string kClient = RADARSLAM_MAP_CLIENT;

std::string expectedGridSha(const fs::path& map_dir, double resolution = 0.2) {
  GridExportParams p;
  p.resolution_m = resolution;
  return dds::gridSha256(dds::gridMessage(loadMap(map_dir), p, 0));
}

std::string yamlValue(const std::string& text, const std::string& key) {
  const auto pos = text.find(key + ": ");
  if (pos == std::string::npos) return "";
  std::string v = text.substr(pos + key.size() + 2, text.find('\n', pos) - pos - key.size() - 2);
  if (v.size() >= 2 && v.front() == '"') v = v.substr(1, v.size() - 2);
  return v;
}

std::vector<std::string> serverArgs(const fs::path& map, unsigned domain,
                                    std::vector<std::string> extra = {}) {
  std::vector<std::string> a{kServer, "--map", map.string(), "--domain", std::to_string(domain)};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}
std::vector<std::string> clientArgs(const fs::path& out, unsigned domain, std::vector<std::string> extra = {},
                                    const std::string& timeout_s = "15") {
  std::vector<std::string> a{kClient,     "-o",     out.string(), "--domain", std::to_string(domain),
                             "--timeout", timeout_s};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

// The body of a PCD file after its header (the binary points).
std::string pcdBody(const fs::path& p) {
  const std::string t = test::readText(p);
  const auto pos = t.find("DATA binary\n");
  return pos == std::string::npos ? "" : t.substr(pos + 12);
}

TEST(MapServer, LateJoinerReceivesEveryLayerIdenticalToTheMapFiles) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "campus";
  const KeyframeMap map = test::syntheticMap(6, 300, 40.0, 1);
  saveMap(map, map_dir);
  const unsigned dom = test::testDomainId(0);

  Child server(serverArgs(map_dir, dom), tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map 'campus' revision 1", 15)) << server.err();
  // Late joiner: the server published before this client existed (latched, TRANSIENT_LOCAL).
  Child client(clientArgs(tmp.path() / "got", dom), tmp.path() / "client");
  ASSERT_EQ(client.wait(20), 0) << client.err();

  const std::string info = test::readText(tmp.path() / "got" / "map_info.yaml");
  EXPECT_EQ(yamlValue(info, "grid_sha256"), expectedGridSha(map_dir));
  EXPECT_EQ(yamlValue(info, "map_name"), "campus");
  EXPECT_EQ(yamlValue(info, "keyframes"), "6");
  EXPECT_EQ(yamlValue(info, "revision"), "1");
  EXPECT_EQ(yamlValue(info, "manifest_sha256"), sha256Hex(test::readText(map_dir / "manifest.yaml")));

  // Cloud and OctoMap: byte-identical to the map module's own exports.
  const fs::path exp = tmp.path() / "exports";
  exportPointCloud(map, exp, "cloud");
  exportOctomap(map, exp, "map");
  EXPECT_EQ(pcdBody(tmp.path() / "got" / "cloud.pcd"), pcdBody(exp / "cloud.pcd"));
  EXPECT_FALSE(pcdBody(exp / "cloud.pcd").empty());
  EXPECT_EQ(test::readText(tmp.path() / "got" / "map.bt"), test::readText(exp / "map.bt"));

  // Grid image: the same size as the grid, with occupied (dark), free (bright) and unknown cells.
  const OccupancyRaster raster = buildOccupancy(map);
  const cv::Mat img = cv::imread((tmp.path() / "got" / "grid.pgm").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, raster.width);
  EXPECT_EQ(img.rows, raster.height);
  EXPECT_EQ(img.at<unsigned char>(0, 0), 205);  // a margin corner: never observed
  int dark = 0, bright = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      dark += img.at<unsigned char>(r, c) < 100;
      bright += img.at<unsigned char>(r, c) > 210;
    }
  EXPECT_GT(dark, 100);
  EXPECT_GT(bright, 1000);
  EXPECT_NE(test::readText(tmp.path() / "got" / "grid.yaml").find("resolution: 0.2\n"), std::string::npos);

  server.signal(SIGTERM);
  EXPECT_EQ(server.wait(10), 0) << server.err();
  EXPECT_TRUE(server.waitForLog("shutting down", 1)) << server.err();
}

TEST(MapServer, EightConcurrentSubscribersAllReceiveTheGrid) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "m";
  saveMap(test::syntheticMap(4, 200, 30.0, 2), map_dir);
  const unsigned dom = test::testDomainId(1);
  const std::string sha = expectedGridSha(map_dir);
  Child server(serverArgs(map_dir, dom, {"--layers", "grid"}), tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map", 15)) << server.err();
  std::vector<std::unique_ptr<Child>> clients;
  for (int i = 0; i < 8; ++i)
    clients.push_back(
        std::make_unique<Child>(clientArgs(tmp.path() / ("c" + std::to_string(i)), dom, {"--layers", "grid"}),
                                tmp.path() / ("client" + std::to_string(i))));
  for (int i = 0; i < 8; ++i) {
    ASSERT_EQ(clients[i]->wait(25), 0) << "client " << i << ": " << clients[i]->err();
    EXPECT_EQ(
        yamlValue(test::readText(tmp.path() / ("c" + std::to_string(i)) / "map_info.yaml"), "grid_sha256"),
        sha);
  }
}

TEST(MapServer, LargeGrid4000x4000) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "big";
  // Points over [-95, 95]^2 m, 5 m margin, 0.05 m cells: 200 m / 0.05 m = 4000 cells a side.
  saveMap(test::syntheticMap(3, 2000, 95.0, 3), map_dir);
  const unsigned dom = test::testDomainId(2);
  Child server(serverArgs(map_dir, dom, {"--layers", "grid", "--resolution", "0.05"}), tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map", 20)) << server.err();
  Child client(clientArgs(tmp.path() / "got", dom, {"--layers", "grid"}), tmp.path() / "client");
  ASSERT_EQ(client.wait(20), 0) << client.err();
  EXPECT_EQ(yamlValue(test::readText(tmp.path() / "got" / "map_info.yaml"), "grid_sha256"),
            expectedGridSha(map_dir, 0.05));
  const cv::Mat img = cv::imread((tmp.path() / "got" / "grid.pgm").string(), cv::IMREAD_UNCHANGED);
  EXPECT_GE(img.cols, 4000);
  EXPECT_GE(img.rows, 4000);
  EXPECT_LE(img.cols, 4002);
}

TEST(MapServer, ReloadsAChangedMapAndSurvivesARestart) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "site";
  saveMap(test::syntheticMap(4, 200, 30.0, 4), map_dir);
  const std::string sha_a = expectedGridSha(map_dir);
  const unsigned dom = test::testDomainId(3);
  auto server = std::make_unique<Child>(serverArgs(map_dir, dom, {"--layers", "grid", "--poll", "0.2"}),
                                        tmp.path() / "server1");
  ASSERT_TRUE(server->waitForLog("revision 1", 15)) << server->err();
  {
    Child first(clientArgs(tmp.path() / "a", dom, {"--layers", "grid"}), tmp.path() / "a");
    ASSERT_EQ(first.wait(20), 0) << first.err();
    EXPECT_EQ(yamlValue(test::readText(tmp.path() / "a" / "map_info.yaml"), "grid_sha256"), sha_a);
  }
  // Rewrite the map while the server runs: saveMap swaps the directory atomically.
  saveMap(test::syntheticMap(5, 250, 35.0, 5), map_dir);
  const std::string sha_b = expectedGridSha(map_dir);
  ASSERT_NE(sha_a, sha_b);
  Child second(clientArgs(tmp.path() / "b", dom, {"--layers", "grid", "--expect-grid-sha256", sha_b}),
               tmp.path() / "b");
  ASSERT_EQ(second.wait(20), 0) << second.err() << server->err();
  EXPECT_EQ(yamlValue(test::readText(tmp.path() / "b" / "map_info.yaml"), "revision"), "2");
  EXPECT_TRUE(server->waitForLog("revision 2", 1)) << server->err();

  // SIGHUP forces a reload (same map: revision 3).
  server->signal(SIGHUP);
  EXPECT_TRUE(server->waitForLog("revision 3", 15)) << server->err();

  // Restart: stop the server, start a client with no server running, then the server again.
  server->signal(SIGINT);
  ASSERT_EQ(server->wait(10), 0) << server->err();
  Child late(clientArgs(tmp.path() / "c", dom, {"--layers", "grid"}), tmp.path() / "late");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_TRUE(late.running());
  server = std::make_unique<Child>(serverArgs(map_dir, dom, {"--layers", "grid"}), tmp.path() / "server2");
  ASSERT_EQ(late.wait(20), 0) << late.err() << server->err();
  EXPECT_EQ(yamlValue(test::readText(tmp.path() / "c" / "map_info.yaml"), "grid_sha256"), sha_b);
}

TEST(MapServer, KilledAndFrozenClientsDoNotDisturbTheOthersOrReloads) {
  test::TempDir tmp;
  const fs::path map_dir = tmp.path() / "big";
  saveMap(test::syntheticMap(3, 1000, 60.0, 6), map_dir);  // ~2600 x 2600 cells (6.8 MB) at 0.05 m
  const unsigned dom = test::testDomainId(4);
  Child server(serverArgs(map_dir, dom, {"--layers", "grid", "--resolution", "0.05", "--poll", "0.2"}),
               tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map", 20)) << server.err();
  const std::vector<std::string> grid_only{"--layers", "grid"};
  // One client is killed while it receives the grid, one is frozen (SIGSTOP: a reliable reader
  // that stops acknowledging) for the rest of the test. The killed one waits for a grid that never
  // comes: the map arrives in well under the 50 ms before the kill, and a client that had exited
  // with it would not test a reader dying while subscribed.
  Child killed(clientArgs(tmp.path() / "killed", dom, {"--layers", "grid", "--expect-grid-sha256", "none"}),
               tmp.path() / "killed");
  Child frozen(
      clientArgs(tmp.path() / "frozen", dom, {"--layers", "grid", "--expect-grid-sha256", "none"}, "60"),
      tmp.path() / "frozen");
  ASSERT_TRUE(killed.waitForLog("waiting for the map", 15)) << killed.err();
  ASSERT_TRUE(frozen.waitForLog("waiting for the map", 15)) << frozen.err();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  killed.signal(SIGKILL);
  frozen.signal(SIGSTOP);
  EXPECT_EQ(killed.wait(5), 128 + SIGKILL);

  const std::string sha = expectedGridSha(map_dir, 0.05);
  std::vector<std::unique_ptr<Child>> clients;
  for (int i = 0; i < 2; ++i)
    clients.push_back(
        std::make_unique<Child>(clientArgs(tmp.path() / ("c" + std::to_string(i)), dom, grid_only),
                                tmp.path() / ("client" + std::to_string(i))));
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(clients[i]->wait(20), 0) << clients[i]->err();
    EXPECT_EQ(
        yamlValue(test::readText(tmp.path() / ("c" + std::to_string(i)) / "map_info.yaml"), "grid_sha256"),
        sha);
  }
  // A reload still goes out with the frozen reader around, and newcomers get it.
  saveMap(test::syntheticMap(3, 1000, 60.0, 16), map_dir);
  const std::string sha2 = expectedGridSha(map_dir, 0.05);
  EXPECT_TRUE(server.waitForLog("revision 2", 20)) << server.err();
  Child after(clientArgs(tmp.path() / "after", dom, {"--layers", "grid", "--expect-grid-sha256", sha2}),
              tmp.path() / "after");
  ASSERT_EQ(after.wait(20), 0) << after.err();
  EXPECT_TRUE(server.running());
  frozen.signal(SIGKILL);
}

// One line on stderr, naming the problem, and a non-zero exit.
void expectOneLineError(Child& c, int code, const std::string& needle) {
  ASSERT_EQ(c.wait(15), code) << c.err();
  const std::string e = c.err();
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
  EXPECT_NE(e.find("error: "), std::string::npos) << e;
  EXPECT_NE(e.find(needle), std::string::npos) << e;
}

TEST(MapServer, BadInputGivesOneLineErrors) {
  test::TempDir tmp;
  const unsigned dom = test::testDomainId(5);
  {
    Child c(serverArgs(tmp.path() / "nonexistent", dom), tmp.path() / "nomap");
    expectOneLineError(c, 1, "no such map directory");
  }
  fs::create_directories(tmp.path() / "broken");
  {
    Child c(serverArgs(tmp.path() / "broken", dom), tmp.path() / "broken");
    expectOneLineError(c, 1, "manifest.yaml");
  }
  saveMap(test::syntheticMap(2, 50, 10.0, 7), tmp.path() / "ok");
  {
    Child c(serverArgs(tmp.path() / "ok", dom, {"--config", (tmp.path() / "missing.xml").string()}),
            tmp.path() / "nocfg");
    expectOneLineError(c, 1, "missing.xml");
  }
  {
    std::ofstream(tmp.path() / "bad.xml")
        << "<CycloneDDS><Domain Id=\"any\"><General><NoSuchSetting>1</NoSuchSetting>"
           "</General></Domain></CycloneDDS>";
    Child c(serverArgs(tmp.path() / "ok", dom, {"--config", (tmp.path() / "bad.xml").string()}),
            tmp.path() / "badcfg");
    expectOneLineError(c, 1, "DDS domain");
  }
  {
    Child c(serverArgs(tmp.path() / "ok", dom, {"--layers", "grid,walls"}), tmp.path() / "badlayer");
    expectOneLineError(c, 1, "walls");
  }
  {
    Child c({kServer, "--map", (tmp.path() / "ok").string(), "--bogus"}, tmp.path() / "badopt");
    expectOneLineError(c, 1, "bogus");
  }
  {
    Child c({kClient}, tmp.path() / "noout");
    expectOneLineError(c, 1, "out");
  }
  {  // no server on this domain: the client times out with status 2
    Child c(clientArgs(tmp.path() / "x", dom, {"--verbosity", "WARN"}, "0.5"), tmp.path() / "timeout");
    expectOneLineError(c, 2, "timed out");
    EXPECT_FALSE(fs::exists(tmp.path() / "x" / "map_info.yaml"));
  }
}

}  // namespace
}  // namespace radarslam
