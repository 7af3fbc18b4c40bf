// Every export read back by an independent reader and compared with the source map: MRPT's ROS
// map_server loader and .gridmap deserialisation, liboctomap, our own PLY/PCD parsers, MRPT's
// CSimpleMap loader.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/serialization/CArchive.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>

#include "file_contents.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/map_exports.h"
#include "synthetic_map.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace radarslam;

namespace {

using radarslam::test::readFileBytes;

struct Xyzi {
  float x, y, z, i;
};

// All keyframe points in the map frame, in export order.
std::vector<Xyzi> expectedCloud(const KeyframeMap& map) {
  std::vector<Xyzi> out;
  for (const auto& kf : map.keyframes) {
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points)
      out.push_back(
          {float(kf.pose.x + c * p.x - s * p.y), float(kf.pose.y + s * p.x + c * p.y), 0.f, p.power});
  }
  return out;
}

// Minimal PLY/PCD parsers: header lines up to the end marker, then packed little-endian float32.
std::vector<Xyzi> parseBinaryBody(const std::string& bytes, std::size_t body, std::size_t n) {
  EXPECT_EQ(bytes.size() - body, n * 16);
  std::vector<Xyzi> pts(n);
  if (bytes.size() - body == n * 16) std::memcpy(pts.data(), bytes.data() + body, n * 16);
  return pts;
}

std::vector<Xyzi> parsePly(const fs::path& path) {
  const std::string bytes = readFileBytes(path);
  std::istringstream in(bytes);
  std::string line;
  std::size_t n = 0;
  std::vector<std::string> props;
  std::getline(in, line);
  EXPECT_EQ(line, "ply");
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream ls(line);
    std::string w;
    ls >> w;
    if (w == "format") {
      ls >> w;
      EXPECT_EQ(w, "binary_little_endian");
    } else if (w == "element") {
      ls >> w >> n;
      EXPECT_EQ(w, "vertex");
    } else if (w == "property") {
      std::string type, name;
      ls >> type >> name;
      EXPECT_EQ(type, "float");
      props.push_back(name);
    }
  }
  EXPECT_EQ(props, (std::vector<std::string>{"x", "y", "z", "intensity"}));
  return parseBinaryBody(bytes, static_cast<std::size_t>(in.tellg()), n);
}

std::vector<Xyzi> parsePcd(const fs::path& path) {
  const std::string bytes = readFileBytes(path);
  std::istringstream in(bytes);
  std::string line;
  std::size_t n = 0, width = 0;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string key, rest;
    ls >> key;
    std::getline(ls, rest);
    if (key == "VERSION") {
      EXPECT_EQ(rest, " 0.7");
    }
    if (key == "FIELDS") {
      EXPECT_EQ(rest, " x y z intensity");
    }
    if (key == "SIZE") {
      EXPECT_EQ(rest, " 4 4 4 4");
    }
    if (key == "TYPE") {
      EXPECT_EQ(rest, " F F F F");
    }
    if (key == "WIDTH") width = std::stoul(rest);
    if (key == "POINTS") n = std::stoul(rest);
    if (key == "DATA") {
      EXPECT_EQ(rest, " binary");
      break;
    }
  }
  EXPECT_EQ(width, n);
  return parseBinaryBody(bytes, static_cast<std::size_t>(in.tellg()), n);
}

void expectSameCloud(const std::vector<Xyzi>& got, const std::vector<Xyzi>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].x, want[i].x) << i;
    ASSERT_EQ(got[i].y, want[i].y) << i;
    ASSERT_EQ(got[i].z, 0.f) << i;
    ASSERT_EQ(got[i].i, want[i].i) << i;
  }
}

}  // namespace

TEST(MapExports, OccupancyRasterMarksLandmarksOccupiedAndTheInsideFree) {
  const KeyframeMap map = test::syntheticMap();
  const OccupancyRaster r = buildOccupancy(map);
  ASSERT_GT(r.width, 0);
  auto cell = [&](double x, double y) {
    return r.at(int(std::floor((x - r.x_min) / r.resolution)), int(std::floor((y - r.y_min) / r.resolution)));
  };
  for (const auto& p : map.points) EXPECT_GT(cell(p.x, p.y), 0.65f) << p.id;
  for (const auto& kf : map.keyframes) EXPECT_LT(cell(kf.pose.x, kf.pose.y), 0.196f) << kf.id;
  EXPECT_LT(cell(0.0, 10.0), 0.196f);                             // inside the ring: seen free
  EXPECT_FLOAT_EQ(cell(test::kLandmarkRadius + 3.0, 0.0), 0.5f);  // behind the ring: never observed
}

TEST(MapExports, GridReadBackByMrptRosLoaderAndGridmap) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap();
  GridExportParams params;
  params.resolution_m = 0.25;
  const auto files = exportOccupancyGrid(map, tmp.path(), "grid", params);
  EXPECT_EQ(files.size(), 5u);
  const OccupancyRaster r = buildOccupancy(map, params);

  for (const char* yaml : {"grid.png.yaml", "grid.pgm.yaml"}) {
    mrpt::maps::COccupancyGridMap2D ros;
    ASSERT_TRUE(ros.loadFromROSMapServerYAML((tmp / yaml).string())) << yaml;
    EXPECT_NEAR(ros.getResolution(), params.resolution_m, 1e-6);
    EXPECT_EQ(int(ros.getSizeX()), r.width);
    EXPECT_EQ(int(ros.getSizeY()), r.height);
    int occupied = 0;
    for (const auto& p : map.points) {
      EXPECT_LT(ros.getPos(p.x, p.y), 0.35f) << yaml << " landmark " << p.id;  // P(free)
      occupied += ros.getPos(p.x, p.y) < 0.35f;
    }
    EXPECT_EQ(occupied, int(map.points.size()));
    for (const auto& kf : map.keyframes) EXPECT_GT(ros.getPos(kf.pose.x, kf.pose.y), 0.8f) << yaml;
  }

  mrpt::maps::COccupancyGridMap2D grid;
  {
    mrpt::io::CFileGZInputStream f((tmp / "grid.gridmap").string());
    auto arch = mrpt::serialization::archiveFrom(f);
    arch >> grid;
  }
  ASSERT_EQ(int(grid.getSizeX()), r.width);
  ASSERT_EQ(int(grid.getSizeY()), r.height);
  double max_err = 0;
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      const double x = r.x_min + (col + 0.5) * r.resolution, y = r.y_min + (row + 0.5) * r.resolution;
      max_err = std::max(max_err, std::abs(double(grid.getPos(x, y)) - (1.0 - r.at(col, row))));
    }
  EXPECT_LT(max_err, 0.02);  // MRPT stores cells as 8/16-bit log-odds
}

TEST(MapExports, OctomapReadBackByLiboctomap) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap();
  OctomapExportParams params;
  params.resolution_m = 0.2;
  exportOctomap(map, tmp.path(), "map", params);
  const octomap::OcTree bt((tmp / "map.bt").string());
  std::unique_ptr<octomap::AbstractOcTree> abstract(octomap::AbstractOcTree::read((tmp / "map.ot").string()));
  ASSERT_TRUE(abstract);
  auto* ot = dynamic_cast<octomap::OcTree*>(abstract.get());
  ASSERT_NE(ot, nullptr);
  for (const octomap::OcTree* tree : {&bt, static_cast<const octomap::OcTree*>(ot)}) {
    EXPECT_NEAR(tree->getResolution(), params.resolution_m, 1e-9);
    // Every landmark's voxel is occupied. Look it up where keyframe 0's (float) point lands, so
    // a landmark exactly on a voxel boundary (e.g. y = 10.0) is not looked up in its neighbour.
    const auto cloud = expectedCloud(map);
    for (std::size_t l = 0; l < map.points.size(); ++l) {
      ASSERT_NEAR(cloud[l].x, map.points[l].x, 1e-4);
      const auto* node = tree->search(cloud[l].x, cloud[l].y, 0.0);
      ASSERT_NE(node, nullptr) << map.points[l].id;
      EXPECT_TRUE(tree->isNodeOccupied(node)) << map.points[l].id;
    }
    for (const auto& kf : map.keyframes) {
      const auto* node = tree->search(kf.pose.x + 1.0, kf.pose.y, 0.0);  // carved by the rays
      ASSERT_NE(node, nullptr);
      EXPECT_FALSE(tree->isNodeOccupied(node));
    }
    EXPECT_EQ(tree->search(test::kLandmarkRadius + 5.0, 0.0, 0.0), nullptr);  // never observed
  }
}

TEST(MapExports, PlyAndPcdParseBackToTheMapPoints) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap();
  exportPointCloud(map, tmp.path(), "cloud");
  const auto want = expectedCloud(map);
  expectSameCloud(parsePly(tmp / "cloud.ply"), want);
  expectSameCloud(parsePcd(tmp / "cloud.pcd"), want);
}

TEST(MapExports, SimpleMapLoadsInMrpt) {
  test::TempDir tmp;
  const KeyframeMap map = test::syntheticMap();
  exportSimpleMap(map, tmp.path(), "map");
  mrpt::maps::CSimpleMap sm;
  ASSERT_TRUE(sm.loadFromFile((tmp / "map.simplemap").string()));
  ASSERT_EQ(sm.size(), map.keyframes.size());
  for (std::size_t i = 0; i < sm.size(); ++i) {
    mrpt::poses::CPose3DPDF::Ptr pdf;
    mrpt::obs::CSensoryFrame::Ptr sf;
    sm.get(i, pdf, sf);
    const auto pose = pdf->getMeanVal();
    const auto& kf = map.keyframes[i];
    EXPECT_NEAR(pose.x(), kf.pose.x, 1e-9);
    EXPECT_NEAR(pose.y(), kf.pose.y, 1e-9);
    EXPECT_NEAR(pose.yaw(), mrpt::math::wrapToPi(kf.pose.phi), 1e-9);
    auto obs = sf->getObservationByClass<mrpt::obs::CObservationPointCloud>();
    ASSERT_TRUE(obs);
    ASSERT_TRUE(obs->pointcloud);
    ASSERT_EQ(obs->pointcloud->size(), kf.points.size());
    float x, y, z;
    obs->pointcloud->getPoint(5, x, y, z);
    EXPECT_EQ(x, kf.points[5].x);
    EXPECT_EQ(y, kf.points[5].y);
  }
}

TEST(MapExports, EmptyMapGridIsAnInputError) {
  test::TempDir tmp;
  EXPECT_THROW(exportOccupancyGrid(KeyframeMap{}, tmp.path()), InputError);
}
