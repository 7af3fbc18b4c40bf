// The directly encoded OctoMap slab (octomap_slab.h) is byte-identical to what liboctomap writes
// for the same voxels, and liboctomap reads it back cell for cell as the occupancy raster.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "radarslam/core/errors.h"
#include "radarslam/map/map_exports.h"
#include "radarslam/map/octomap_slab.h"
#include "synthetic_map.h"

using namespace radarslam;

namespace {

// The reference: an octomap::OcTree with one voxel per observed raster cell, set through the API.
std::unique_ptr<octomap::OcTree> referenceTree(const OccupancyRaster& r) {
  auto tree = std::make_unique<octomap::OcTree>(r.resolution);
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * r.width + col;
      if (!r.observed[i]) continue;
      const float p = r.p_occupied[i];
      const octomap::point3d centre(static_cast<float>(r.x_min + (col + 0.5) * r.resolution),
                                    static_cast<float>(r.y_min + (row + 0.5) * r.resolution),
                                    static_cast<float>(0.5 * r.resolution));
      tree->setNodeValue(centre, std::log(p / (1.0f - p)), /*lazy_eval=*/true);
    }
  tree->updateInnerOccupancy();
  return tree;
}

std::string binaryOf(const octomap::OcTree& t) {
  std::ostringstream os(std::ios::binary);
  t.writeBinaryConst(os);
  return os.str();
}

std::string fullOf(const octomap::OcTree& t) {
  std::ostringstream os(std::ios::binary);
  t.write(os);
  return os.str();
}

}  // namespace

TEST(OctomapSlab, ByteIdenticalToLiboctomapsOwnWriters) {
  for (const double res : {0.2, 0.5}) {
    GridExportParams gp;
    gp.resolution_m = res;
    const OccupancyRaster r = buildOccupancy(test::syntheticMap(), gp);
    const auto tree = referenceTree(r);
    const OctomapSlab slab = encodeOctomapSlab(r);
    ASSERT_GT(slab.leaves, 1000u);
    EXPECT_EQ(slab.nodes, tree->size());
    EXPECT_EQ(slab.leaves, tree->getNumLeafNodes());
    EXPECT_TRUE(octomapBinaryFile(slab) == binaryOf(*tree)) << "binary stream differs at resolution " << res;
    const std::string ours = octomapFullFile(slab), theirs = fullOf(*tree);
    std::size_t at = 0;
    while (at < ours.size() && at < theirs.size() && ours[at] == theirs[at]) ++at;
    EXPECT_TRUE(ours == theirs)
        << "full stream differs at resolution " << res << " from byte " << at << " of " << ours.size()
        << " / " << theirs.size() << ": "
        << ours.substr(0, std::min<std::size_t>(at + 8, ours.size())).substr(at > 8 ? at - 8 : 0);
  }
}

TEST(OctomapSlab, ReadBackByLiboctomapMatchesTheRasterCellForCell) {
  const OccupancyRaster r = buildOccupancy(test::syntheticMap());
  const OctomapSlab slab = encodeOctomapSlab(r);
  std::istringstream in(octomapBinaryFile(slab));
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(in));
  EXPECT_NEAR(tree.getResolution(), r.resolution, 1e-12);
  std::size_t occupied = 0, free = 0;
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * r.width + col;
      const auto* node = tree.search(r.x_min + (col + 0.5) * r.resolution,
                                     r.y_min + (row + 0.5) * r.resolution, 0.5 * r.resolution);
      if (!r.observed[i]) {
        ASSERT_EQ(node, nullptr) << col << "," << row;
        continue;
      }
      ASSERT_NE(node, nullptr) << col << "," << row;
      const bool occ = r.p_occupied[i] > 0.5f;
      ASSERT_EQ(tree.isNodeOccupied(node), occ) << col << "," << row;
      (occ ? occupied : free)++;
    }
  EXPECT_GT(occupied, 100u);
  EXPECT_GT(free, 1000u);
  // Nothing above or below the slab.
  EXPECT_EQ(tree.search(r.x_min + r.width / 2 * r.resolution, r.y_min + r.height / 2 * r.resolution,
                        1.5 * r.resolution),
            nullptr);
}

TEST(OctomapSlab, EmptyRasterHasNoRoot) {
  OccupancyRaster r;
  r.width = 4, r.height = 3;
  r.p_occupied.assign(12, 0.5f);
  r.observed.assign(12, 0);
  const OctomapSlab slab = encodeOctomapSlab(r);
  EXPECT_EQ(slab.nodes, 0u);
  EXPECT_TRUE(slab.binary_data.empty());
  std::istringstream in(octomapBinaryFile(slab));
  octomap::OcTree tree(0.1);
  EXPECT_TRUE(tree.readBinary(in));
  EXPECT_EQ(tree.size(), 0u);
}

TEST(OctomapSlab, MapBeyondTheKeyRangeIsRefused) {
  OccupancyRaster r;
  r.resolution = 0.2;
  r.x_min = 6500.0;  // 6500 m + 400 cells * 0.2 m > 32768 * 0.2 m = 6553.6 m
  r.width = 400, r.height = 1;
  r.p_occupied.assign(400, 0.7f);
  r.observed.assign(400, 1);
  try {
    encodeOctomapSlab(r);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("coarser resolution"), std::string::npos) << e.what();
  }
  r.x_min = 6400.0;  // fits
  EXPECT_EQ(encodeOctomapSlab(r).leaves, 400u);
}
