// Interoperability with a second DDS implementation (issue 16): fastdds_interop_client, built on
// eProsima Fast DDS with IDL written from the ROS 2 message definitions, reads what our Cyclone DDS
// programs publish on loopback, as a ROS 2 node on rmw_fastrtps would:
//  - every latched layer of radarslam-map-server as a late joiner, the grid's SHA-256 equal to the
//    one in MapInfo, to our own map client's and to the grid the map module computes;
//  - the pose stream of `radarslam localize --publish`, every pose equal to the TUM/CSV outputs.
// docs/dds.md, "Interoperability with Fast DDS".
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <radarslam/dds/map_messages.h>
#include <radarslam/map/map_io.h>
#include <radarslam/map/sha256.h>

#include "dds_test_util.h"
#include "simulated_dataset.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

namespace fs = std::filesystem;
using test::Child;

// Fast DDS quirks (docs/dds.md): ~15 % of late joins find the Cyclone participants ~1 s later.
// These bound a hang only; the receive times are printed, not asserted.
constexpr double kClientTimeoutS = 30;

/// Data rows (not starting with '#') of a whitespace-separated file.
std::vector<std::vector<std::string>> rows(const fs::path& p) {
  std::vector<std::vector<std::string>> out;
  std::ifstream f(p);
  for (std::string line; std::getline(f, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> cols;
    for (std::string c; ss >> c;) cols.push_back(c);
    out.push_back(cols);
  }
  return out;
}

/// One line of the client: its first word and its key=value fields.
struct Line {
  std::string kind;  // "received", "pose", "matched", "summary"
  std::string what;  // for "received": map, cloud, octomap, map_info
  std::map<std::string, std::string> kv;
};
std::vector<Line> parse(const std::string& out) {
  std::vector<Line> lines;
  std::istringstream in(out);
  for (std::string text; std::getline(in, text);) {
    std::istringstream ws(text);
    Line l;
    ws >> l.kind;
    if (l.kind == "received" || l.kind == "matched") ws >> l.what;
    for (std::string w; ws >> w;)
      if (const auto eq = w.find('='); eq != std::string::npos) l.kv[w.substr(0, eq)] = w.substr(eq + 1);
    lines.push_back(l);
  }
  return lines;
}
std::map<std::string, Line> received(const std::vector<Line>& lines) {
  std::map<std::string, Line> r;
  for (const auto& l : lines)
    if (l.kind == "received") r[l.what] = l;
  return r;
}

std::string yamlValue(const std::string& text, const std::string& key) {
  const auto pos = text.find(key + ": ");
  if (pos == std::string::npos) return "";
  std::string v = text.substr(pos + key.size() + 2, text.find('\n', pos) - pos - key.size() - 2);
  if (v.size() >= 2 && v.front() == '"') v = v.substr(1, v.size() - 2);
  return v;
}

/// What follows `marker` in a file (a PCD's binary points, a .bt file's tree).
std::string bodyAfter(const fs::path& p, const std::string& marker) {
  const std::string t = test::readText(p);
  const auto pos = t.find(marker);
  return pos == std::string::npos ? "" : t.substr(pos + marker.size());
}

/// Runs `radarslam ARGS` to completion; returns the exit code (stderr in `log`.err).
int runCli(const std::vector<std::string>& args, const fs::path& log, double timeout_s = 120) {
  std::vector<std::string> all{RADARSLAM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  Child c(all, log);
  return c.wait(timeout_s);
}

/// A 40-scan simulated drive (test/support/simulated_dataset.h: simulated once for all tests, read
/// only) and a map-synth map of it (ground-truth keyframes): a 1969 x 1658 grid (3.3 MB, so 55
/// fragments of 60 000 B), a 22 201-point cloud and a 0.1 MB OctoMap.
struct SmallWorld {
  test::TempDir tmp;
  fs::path data = test::simulatedDataset("--scans 40"), map = tmp.path() / "map";
  SmallWorld() {
    EXPECT_EQ(runCli({"map-synth", data.string(), "-o", map.string()}, tmp.path() / "synth"), 0)
        << test::readText(tmp.path() / "synth.err");
  }
};

std::vector<std::string> fastddsArgs(unsigned domain, const std::string& topics) {
  return {FASTDDS_INTEROP_CLIENT,
          "--domain",
          std::to_string(domain),
          "--topics",
          topics,
          "--timeout",
          std::to_string(kClientTimeoutS * test::timeScale())};
}

TEST(FastDdsInterop, LateJoinerReceivesEveryLatchedLayer) {
  SmallWorld w;
  ASSERT_FALSE(HasFailure());
  const unsigned dom = test::testDomainId(22);
  Child server({RADARSLAM_MAP_SERVER, "--map", w.map.string(), "--domain", std::to_string(dom)},
               w.tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map 'map' revision 1", 30)) << server.err();

  // Late joiner: the layers were published before the Fast DDS participant existed.
  Child fast(fastddsArgs(dom, "map,cloud,octomap,map_info"), w.tmp.path() / "fastdds");
  ASSERT_EQ(fast.wait(kClientTimeoutS + 10), 0) << fast.out() << fast.err();
  std::cout << "fastdds_interop_client:\n" << fast.out();  // receive times (t_ms) for the log
  const auto got = received(parse(fast.out()));
  ASSERT_EQ(got.size(), 4u) << fast.out();
  const auto& grid = got.at("map").kv;
  const auto& cloud = got.at("cloud").kv;
  const auto& octo = got.at("octomap").kv;
  const auto& info = got.at("map_info").kv;

  // Our own (Cyclone DDS) client on the same server: every layer, written to files.
  Child ours({RADARSLAM_MAP_CLIENT, "-o", (w.tmp.path() / "ours").string(), "--domain", std::to_string(dom),
              "--timeout", "30"},
             w.tmp.path() / "ours");
  ASSERT_EQ(ours.wait(40), 0) << ours.err();
  const std::string our_info = test::readText(w.tmp.path() / "ours" / "map_info.yaml");

  // The grid: one SHA-256 everywhere (Fast DDS's OpenSSL hash of the received cells, MapInfo as
  // Fast DDS decoded it, our client's check, the map module's grid of the map on disk).
  GridExportParams gp;  // the server's default resolution, 0.2 m
  const dds::OccupancyGridMsg expected = dds::gridMessage(loadMap(w.map), gp, 0);
  const std::string sha = dds::gridSha256(expected);
  EXPECT_EQ(grid.at("sha256"), sha);
  EXPECT_EQ(info.at("grid_sha256"), sha);
  EXPECT_EQ(yamlValue(our_info, "grid_sha256"), sha);
  EXPECT_EQ(grid.at("width"), std::to_string(expected.width));
  EXPECT_EQ(grid.at("height"), std::to_string(expected.height));
  EXPECT_EQ(grid.at("data_bytes"), std::to_string(expected.data.size()));
  EXPECT_GT(expected.data.size(), 60'000u * 10);  // fragmented: many 60 000 B fragments
  EXPECT_NEAR(std::stod(grid.at("resolution")), 0.2, 1e-6);
  EXPECT_NEAR(std::stod(grid.at("origin_x")), expected.origin.x, 1e-9);
  EXPECT_NEAR(std::stod(grid.at("origin_y")), expected.origin.y, 1e-9);

  // Cloud and OctoMap: the payload bytes equal what our client wrote (PCD points, .bt tree).
  EXPECT_EQ(cloud.at("fields"), "x,y,z,intensity");
  EXPECT_EQ(cloud.at("point_step"), "16");
  const std::string pcd = bodyAfter(w.tmp.path() / "ours" / "cloud.pcd", "DATA binary\n");
  ASSERT_FALSE(pcd.empty());
  EXPECT_EQ(cloud.at("data_bytes"), std::to_string(pcd.size()));
  EXPECT_EQ(cloud.at("sha256"), sha256Hex(pcd));
  EXPECT_EQ(std::stoul(cloud.at("width")) * 16, pcd.size());
  const std::string bt = bodyAfter(w.tmp.path() / "ours" / "map.bt", "\ndata\n");
  ASSERT_FALSE(bt.empty());
  EXPECT_EQ(octo.at("id"), "OcTree");
  EXPECT_EQ(octo.at("binary"), "1");
  EXPECT_EQ(octo.at("data_bytes"), std::to_string(bt.size()));
  EXPECT_EQ(octo.at("sha256"), sha256Hex(bt));

  // MapInfo and the headers: one publication (equal stamps), frame "map".
  EXPECT_EQ(info.at("map_name"), "map");
  EXPECT_EQ(info.at("revision"), "1");
  EXPECT_EQ(info.at("keyframes"), yamlValue(our_info, "keyframes"));
  for (const auto* l : {&grid, &cloud, &octo, &info}) {
    EXPECT_EQ(l->at("stamp"), info.at("stamp"));
    EXPECT_EQ(l->at("frame"), "map");
  }

  server.signal(SIGTERM);
  EXPECT_EQ(server.wait(15), 0) << server.err();
}

TEST(FastDdsInterop, LateJoinerReceivesEveryTileOfATiledMap) {
  SmallWorld w;
  ASSERT_FALSE(HasFailure());
  // The same drive's map with its 1969 x 1658 grid tiled (256-cell tiles, overview downsampled).
  const fs::path tiled = w.tmp.path() / "tiled", config = w.tmp.path() / "tiling.yaml";
  std::ofstream(config) << "map_layers:\n  grid_tile_cells: 256\n  grid_tile_above_cells: 1\n"
                           "  grid_overview_max_cells: 500000\n";
  ASSERT_EQ(runCli({"map-synth", w.data.string(), "-o", tiled.string(), "--config", config.string()},
                   w.tmp.path() / "synth_tiled"),
            0)
      << test::readText(w.tmp.path() / "synth_tiled.err");
  const auto grid_index = rows(tiled / "layers" / "grid_tiles.txt");  // first row: the format line
  const auto cloud_index = rows(tiled / "layers" / "cloud_tiles.txt");
  ASSERT_GT(grid_index.size(), 2u);
  ASSERT_GT(cloud_index.size(), 2u);
  const unsigned dom = test::testDomainId(21);
  Child server({RADARSLAM_MAP_SERVER, "--map", tiled.string(), "--domain", std::to_string(dom)},
               w.tmp.path() / "server");
  ASSERT_TRUE(server.waitForLog("published map 'tiled' revision 1", 30)) << server.err();
  Child fast(fastddsArgs(dom, "map,map_info,map_tiles,cloud_tiles"), w.tmp.path() / "fastdds");
  ASSERT_EQ(fast.wait(kClientTimeoutS + 10), 0) << fast.out() << fast.err();
  const auto lines = parse(fast.out());
  const auto got = received(lines);
  const auto& info = got.at("map_info").kv;
  EXPECT_EQ(info.at("tile_cells"), "256");
  EXPECT_EQ(info.at("tiles"), std::to_string(grid_index.size() - 1));
  EXPECT_EQ(got.at("map").kv.at("sha256"), info.at("overview_sha256"));  // /map is the overview
  // Every grid tile as Fast DDS decoded it: cells hashed by OpenSSL = the tile index on disk.
  std::map<std::string, std::string> want;  // "tx ty" -> sha256
  for (std::size_t i = 1; i < grid_index.size(); ++i)
    want[grid_index[i][0] + " " + grid_index[i][1]] = grid_index[i][2];
  std::size_t tiles = 0;
  std::vector<std::string> cloud_shas;
  for (const auto& l : lines) {
    if (l.kind != "received") continue;
    if (l.what == "map_tile") {
      ++tiles;
      EXPECT_EQ(l.kv.at("sha256"), want[l.kv.at("tile_x") + " " + l.kv.at("tile_y")]) << l.kv.at("tile_x");
      EXPECT_EQ(l.kv.at("sha256"), l.kv.at("cells_sha256"));
      EXPECT_EQ(l.kv.at("stamp"), info.at("stamp"));
    } else if (l.what == "cloud_tile") {
      cloud_shas.push_back(l.kv.at("sha256"));
    }
  }
  EXPECT_EQ(tiles, grid_index.size() - 1);
  ASSERT_EQ(cloud_shas.size(), cloud_index.size() - 1);
  for (std::size_t i = 0; i < cloud_shas.size(); ++i) EXPECT_EQ(cloud_shas[i], cloud_index[i + 1][4]) << i;
  server.signal(SIGTERM);
  EXPECT_EQ(server.wait(15), 0) << server.err();
}

TEST(FastDdsInterop, ReceivesEveryPoseOfLocalize) {
  SmallWorld w;
  ASSERT_FALSE(HasFailure());
  const unsigned dom = test::testDomainId(23);
  // The Fast DDS reader first (VOLATILE, as a ROS 2 subscriber: it sees what is published after it
  // matched); localize waits for it (--wait-subscribers 1), then publishes one pose per localised
  // scan and waits for the acknowledgements before it exits.
  Child fast({FASTDDS_INTEROP_CLIENT, "--domain", std::to_string(dom), "--topics", "pose", "--timeout",
              std::to_string(300 * test::timeScale())},
             w.tmp.path() / "fastdds");
  const fs::path out = w.tmp.path() / "out.tum";
  Child loc({RADARSLAM_CLI, "localize", w.map.string(), w.data.string(), "-o", out.string(), "--publish",
             "--domain", std::to_string(dom), "--wait-subscribers", "1", "--dds-timeout",
             std::to_string(kClientTimeoutS), "-q"},
            w.tmp.path() / "loc");
  ASSERT_EQ(loc.wait(180), 0) << loc.err() << fast.out() << fast.err();
  const auto tum = rows(out);
  std::vector<std::vector<std::string>> side;
  for (const auto& r : rows(out.string() + ".csv"))
    if (r[3] == "1") side.push_back(r);
  ASSERT_GE(tum.size(), 30u) << loc.out();  // the localiser itself works on this world
  ASSERT_EQ(side.size(), tum.size());

  // Every pose was acknowledged before localize exited; give the client's output a moment anyway.
  auto poses = [&] {
    std::vector<Line> p;
    for (auto& l : parse(fast.out()))
      if (l.kind == "pose") p.push_back(l);
    return p;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (poses().size() < tum.size() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  fast.signal(SIGTERM);
  ASSERT_EQ(fast.wait(15), 0) << fast.out() << fast.err();
  const auto got = poses();
  ASSERT_EQ(got.size(), tum.size()) << fast.out();

  for (std::size_t i = 0; i < got.size(); ++i) {
    const auto& m = got[i].kv;
    const auto& t = tum[i];
    EXPECT_EQ(m.at("frame"), "map") << i;
    EXPECT_EQ(m.at("stamp"), t[0]) << i;  // SEC.NANOSEC, as the TUM file writes stamps
    EXPECT_NEAR(std::stod(m.at("x")), std::stod(t[1]), 1e-6) << i;
    EXPECT_NEAR(std::stod(m.at("y")), std::stod(t[2]), 1e-6) << i;
    EXPECT_EQ(std::stod(m.at("z")), 0.0) << i;
    EXPECT_NEAR(std::stod(m.at("qz")), std::stod(t[6]), 1e-6) << i;
    EXPECT_NEAR(std::stod(m.at("qw")), std::stod(t[7]), 1e-6) << i;
    // Covariance: (x, y, phi) at the (x, y, rot z) entries of the 6x6 ROS layout; CSV has 6 digits.
    std::vector<double> cov;
    std::istringstream cs(m.at("cov"));
    for (std::string c; std::getline(cs, c, ',');) cov.push_back(std::stod(c));
    ASSERT_EQ(cov.size(), 36u) << i;
    const double cxx = std::stod(side[i][7]), cxy = std::stod(side[i][8]), cxp = std::stod(side[i][9]);
    const double cyy = std::stod(side[i][10]), cyp = std::stod(side[i][11]), cpp = std::stod(side[i][12]);
    auto near = [](double a, double b) { return std::abs(a - b) <= 1e-5 * std::abs(b) + 1e-15; };
    EXPECT_TRUE(near(cov[0], cxx)) << i << " " << cov[0] << " vs " << cxx;
    EXPECT_TRUE(near(cov[1], cxy)) << i;
    EXPECT_TRUE(near(cov[6], cxy)) << i;
    EXPECT_TRUE(near(cov[5], cxp)) << i;
    EXPECT_TRUE(near(cov[30], cxp)) << i;
    EXPECT_TRUE(near(cov[7], cyy)) << i;
    EXPECT_TRUE(near(cov[11], cyp)) << i;
    EXPECT_TRUE(near(cov[35], cpp)) << i;
    EXPECT_GT(cov[0], 0) << i;
  }
  std::cout << "fastdds_interop_client: " << got.size()
            << " poses, first at t_ms=" << got.front().kv.at("t_ms")
            << ", last at t_ms=" << got.back().kv.at("t_ms") << "\n";
}

TEST(FastDdsInterop, ClientFailsWithoutPublisherAndOnBadArguments) {
  test::TempDir tmp;
  // Nobody publishes on this domain: exit 2 after the timeout, nothing received.
  Child idle({FASTDDS_INTEROP_CLIENT, "--domain", std::to_string(test::testDomainId(24)), "--timeout", "1"},
             tmp.path() / "idle");
  EXPECT_EQ(idle.wait(20), 2) << idle.out() << idle.err();
  EXPECT_NE(idle.out().find("map=0 cloud=0 octomap=0 map_info=0 exit=2"), std::string::npos) << idle.out();
  EXPECT_EQ(idle.out().find("received"), std::string::npos) << idle.out();
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{FASTDDS_INTEROP_CLIENT, "--timeout", "1"},
        {FASTDDS_INTEROP_CLIENT, "--domain", "233"},
        {FASTDDS_INTEROP_CLIENT, "--domain", std::to_string(test::testDomainId(24)), "--topics", "map,nosuch",
         "--timeout", "1"}}) {
    Child c(bad, tmp.path() / "bad");
    EXPECT_EQ(c.wait(20), 1) << bad.back() << c.err();
  }
}

}  // namespace
}  // namespace radarslam
