// `radarslam map` end to end on short simulated drives: the map directory (loadable map,
// trajectory, grid preview, loops, summary), --threads 1 determinism, extending a map with a
// second traversal (--extend), and one-line errors for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "file_contents.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/trajectory_files.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"
#include "simulated_dataset.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using Result = radarslam::test::CliResult;
using radarslam::test::runCli;

/// The layers saved with the map: listed with matching checksums, equal to the grid built now.
void expectSavedLayers(const fs::path& map) {
  const radarslam::MapManifestSummary s = radarslam::readMapManifest(map);
  EXPECT_EQ(s.format_version, radarslam::kMapFormatVersion);
  ASSERT_TRUE(s.layers.has_value());
  ASSERT_EQ(s.layers->files.size(), 4u);
  for (const auto& f : s.layers->files) {
    const std::string bytes = radarslam::test::readFileBytes(map / f.name);
    EXPECT_EQ(bytes.size(), f.bytes) << f.name;
    EXPECT_EQ(radarslam::sha256Hex(bytes), f.sha256) << f.name;
  }
  EXPECT_EQ(radarslam::readGridLayer(map, *s.layers), radarslam::occupancyCells(radarslam::buildOccupancy(
                                                          radarslam::loadMap(map), s.layers->params.grid)));
}

/// Two short drives through the same simulated world (traversal 2: other lane, other traffic),
/// simulated once for the whole suite.
class CliMap : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    for (const int t : {1, 2})
      data_[t - 1] =
          new fs::path(radarslam::test::simulatedDataset("--scans 50 --traversal " + std::to_string(t)));
  }
  static void TearDownTestSuite() {
    for (fs::path*& p : data_) {
      delete p;
      p = nullptr;
    }
  }
  /// The drive of `traversal` (1 or 2): shared by the tests, read only (test::simulatedDataset).
  static fs::path data(int traversal) { return *data_[traversal - 1]; }
  static fs::path* data_[2];
  radarslam::test::TempDir tmp_;
};
fs::path* CliMap::data_[2] = {nullptr, nullptr};

TEST_F(CliMap, WritesALoadableMapWithTrajectoryPreviewAndSummary) {
  const fs::path map = tmp_ / "maps" / "drive";
  const Result r =
      runCli("map '" + data(1).string() + "' -o '" + map.string() + "' --threads 1", tmp_.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const radarslam::KeyframeMap m = radarslam::loadMap(map);
  EXPECT_GT(m.keyframes.size(), 20u);
  EXPECT_EQ(m.edges.size() + 1, m.keyframes.size());  // a chain of odometry edges, no loop on 50 scans
  EXPECT_GT(m.points.size(), 50u);
  EXPECT_EQ(m.meta.sensor.num_bins, 3768u);
  const radarslam::Trajectory t = radarslam::readTumTrajectory(map / "trajectory.tum");
  ASSERT_EQ(t.size(), 50u);
  // Accuracy against the simulator's ground truth: the end point within 2 % of the path.
  const auto reader = radarslam::openDataset(data(1));
  // (The simulator's relative ground truth covers the scans between the first and the last.)
  const auto& a = t[1];
  const auto& b = t[t.size() - 2];
  const auto g0 = reader->groundTruthAt(a.stamp), g1 = reader->groundTruthAt(b.stamp);
  ASSERT_TRUE(g0 && g1);
  const auto g = *g1 - *g0;
  const auto e = b.pose - a.pose;
  const double path = std::hypot(g.x, g.y);
  EXPECT_GT(path, 50.0);
  EXPECT_LT(std::hypot(e.x - g.x, e.y - g.y), 0.02 * path);
  for (const char* f :
       {"odometry.tum", "grid.png", "grid.pgm.yaml", "loops.csv", "summary.txt", "eval/report.json"})
    EXPECT_TRUE(fs::exists(map / f)) << f;
  EXPECT_NE(r.out.find("map summary"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("accuracy"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("peak RSS"), std::string::npos) << r.out;
  expectSavedLayers(map);
}

TEST_F(CliMap, OneThreadIsDeterministic) {
  const fs::path a = tmp_ / "a", b = tmp_ / "b";
  ASSERT_EQ(
      runCli("map '" + data(1).string() + "' -o '" + a.string() + "' --threads 1 --count 25 -q", tmp_.path())
          .code,
      0);
  ASSERT_EQ(
      runCli("map '" + data(1).string() + "' -o '" + b.string() + "' --threads 1 --count 25 -q", tmp_.path())
          .code,
      0);
  const std::string ta = radarslam::test::readFileBytes(a / "trajectory.tum"),
                    tb = radarslam::test::readFileBytes(b / "trajectory.tum");
  EXPECT_FALSE(ta.empty());
  EXPECT_EQ(ta, tb);
  EXPECT_EQ(radarslam::loadMap(a).keyframes, radarslam::loadMap(b).keyframes);
}

TEST_F(CliMap, ExtendsAMapWithASecondTraversal) {
  const fs::path map = tmp_ / "maps" / "world";
  ASSERT_EQ(
      runCli("map '" + data(1).string() + "' -o '" + map.string() + "' --threads 1 -q", tmp_.path()).code, 0);
  const std::size_t before = radarslam::loadMap(map).keyframes.size();
  // Into the same map directory: the result replaces it atomically.
  const Result r = runCli("map '" + data(2).string() + "' --extend '" + map.string() + "' -o '" +
                              map.string() + "' --threads 1 -q",
                          tmp_.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("anchored"), std::string::npos) << r.err;
  const radarslam::KeyframeMap m = radarslam::loadMap(map);
  // The second drive follows the same streets: where the first covers them it adds no keyframe
  // (map/keyframe_culling.h), so the map grows with the area, not with the driving.
  EXPECT_NE(r.out.find("keyframes dropped where an earlier pass covers the place"), std::string::npos)
      << r.out;
  ASSERT_GE(m.keyframes.size(), before);
  EXPECT_LE(m.keyframes.size(), before + before / 4) << "the revisit added a keyframe at every step";
  std::size_t loops = 0;
  for (const auto& e : m.edges) loops += e.kind == radarslam::EdgeKind::Loop;
  EXPECT_GT(loops, 0u);
  // The second session is in the first one's frame: each keyframe it kept lies near the first
  // session's path (the two drives follow the same streets, lanes ~1.2 m apart).
  for (std::size_t i = before; i < m.keyframes.size(); ++i) {
    double nearest = 1e9;
    for (std::size_t j = 0; j < before; ++j)
      nearest = std::min(nearest, std::hypot(m.keyframes[i].pose.x - m.keyframes[j].pose.x,
                                             m.keyframes[i].pose.y - m.keyframes[j].pose.y));
    EXPECT_LT(nearest, 4.0) << "keyframe " << i;
  }
  // With culling off every keyframe of the second drive stays.
  const fs::path config = tmp_ / "no_culling.yaml";
  {
    std::ofstream c(config);
    c << "slam:\n  keyframe_culling:\n    enabled: false\n";
  }
  const fs::path all = tmp_ / "maps" / "all";
  ASSERT_EQ(runCli("map '" + data(2).string() + "' --extend '" + map.string() + "' -o '" + all.string() +
                       "' --threads 1 -q --config '" + config.string() + "'",
                   tmp_.path())
                .code,
            0);
  EXPECT_GT(radarslam::loadMap(all).keyframes.size(), m.keyframes.size() + before / 2);
}

TEST_F(CliMap, SecondTraversalLocalisesInTheSlamMap) {
  const fs::path map = tmp_ / "maps" / "slam";
  ASSERT_EQ(
      runCli("map '" + data(1).string() + "' -o '" + map.string() + "' --threads 1 -q", tmp_.path()).code, 0);
  const fs::path poses = tmp_ / "poses.tum", eval = tmp_ / "eval";
  const Result r = runCli("localize '" + map.string() + "' '" + data(2).string() + "' -o '" + poses.string() +
                              "' --eval-dir '" + eval.string() + "' -q",
                          tmp_.path());
  ASSERT_EQ(r.code, 0) << r.err;
  // The truth is in the SLAM map's fitted frame; errors come absolute and relative to the map.
  EXPECT_NE(r.out.find("map frame fitted to"), std::string::npos) << r.out;
  std::ifstream csv(eval / "errors.csv");
  std::vector<double> map_err;
  std::size_t rows = 0;
  for (std::string line; std::getline(csv, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> c;
    for (std::string v; ss >> v;) c.push_back(v);
    ASSERT_EQ(c.size(), 11u) << line;
    ++rows;
    map_err.push_back(std::stod(c[9]));
  }
  ASSERT_GE(rows, 45u) << r.out;  // >= 90 % of the 50 scans localised
  std::sort(map_err.begin(), map_err.end());
  EXPECT_LT(map_err[map_err.size() / 2], 0.5) << r.out;  // measured 0.31 m on this 50-scan drive
  EXPECT_LT(map_err.back(), 2.0) << r.out;
  EXPECT_NE(r.out.find("vs the map"), std::string::npos) << r.out;
  // The truth as the map places it (nearest keyframe): one row per localised scan, each at the
  // map-relative error errors.csv reports from the estimate, and the consistency line measured on it.
  EXPECT_NE(r.out.find("consistency    vs the map: NEES mean"), std::string::npos) << r.out;
  auto tum = [](const fs::path& p) {
    std::map<std::string, std::pair<double, double>> xy;
    std::ifstream f(p);
    for (std::string line; std::getline(f, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream ss(line);
      std::string stamp;
      double x = 0, y = 0;
      ss >> stamp >> x >> y;
      xy[stamp] = {x, y};
    }
    return xy;
  };
  const auto est = tum(poses), local = tum(eval / "truth_local.tum");
  ASSERT_EQ(local.size(), rows);
  std::vector<double> local_err;
  for (const auto& [stamp, t] : local) {
    ASSERT_TRUE(est.count(stamp)) << stamp;
    local_err.push_back(std::hypot(est.at(stamp).first - t.first, est.at(stamp).second - t.second));
  }
  std::sort(local_err.begin(), local_err.end());
  EXPECT_NEAR(local_err[local_err.size() / 2], map_err[map_err.size() / 2], 1e-3);
  EXPECT_NEAR(local_err.back(), map_err.back(), 1e-3);
}

TEST_F(CliMap, BadInputGivesOneLineErrors) {
  const auto expectError = [&](const std::string& args, const std::string& needle) {
    const Result r = runCli(args, tmp_.path());
    EXPECT_NE(r.code, 0) << args;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\n" << r.err;
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;
  };
  expectError("map '" + (tmp_ / "missing").string() + "' -o '" + (tmp_ / "m").string() + "'", "no such file");
  expectError("map '" + data(1).string() + "' -o '" + (tmp_ / "m").string() + "' --threads 0", "--threads");
  expectError("map '" + data(1).string() + "' -o '" + (tmp_ / "m").string() + "' --bogus", "bogus");
  expectError("map '" + data(1).string() + "' -o '" + (tmp_ / "m").string() + "' --extend '" +
                  (tmp_ / "nomap").string() + "'",
              "nomap");
  // A map of raw sweeps (map-synth) cannot be extended: SLAM's clouds are motion compensated.
  const fs::path synth = tmp_ / "synth";
  ASSERT_EQ(
      runCli("map-synth '" + data(1).string() + "' -o '" + synth.string() + "' --every 20", tmp_.path()).code,
      0);
  expectError(
      "map '" + data(1).string() + "' -o '" + (tmp_ / "m").string() + "' --extend '" + synth.string() + "'",
      "raw sweeps");
  EXPECT_FALSE(fs::exists(tmp_ / "m"));  // nothing half-written
}

}  // namespace
