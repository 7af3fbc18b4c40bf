#pragma once
// The OctoMap layer of a planar radar map, encoded directly from the occupancy raster.
//
// Every observed cell of the raster becomes the voxel of the one-voxel slab z in [0, resolution)
// above it, with the cell's log-odds (clamped as octomap::OcTree clamps). Such a tree can never be
// pruned (the voxels above and below the slab stay unknown, so no inner node has eight equal
// children), so its OctoMap streams follow from the raster alone: we write them in the OcTree's
// depth-first order without building the tree (which costs ~80 bytes per voxel and a 16-level
// descent per insertion). The streams are byte-identical to octomap::OcTree's writeBinaryData()
// and writeData() for the same voxels (test/map/test_octomap_slab.cpp).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "radarslam/map/map_exports.h"

namespace radarslam {

struct OctomapSlabParams {
  // octomap::OcTree's defaults, as probabilities (0 < min < occupied < max < 1).
  double clamp_min_probability = 0.1192;  ///< clamping_thres_min: log-odds are clamped to it
  double clamp_max_probability = 0.971;   ///< clamping_thres_max
  double occupied_probability = 0.5;      ///< occupancy threshold: occupied iff P > this
  bool full_data = true;                  ///< also encode the .ot stream (log-odds per node)
};

struct OctomapSlab {
  double resolution = 0.2;
  std::size_t nodes = 0;    ///< OcTree::size(): inner nodes and leaves
  std::size_t leaves = 0;   ///< observed cells
  std::string binary_data;  ///< OcTree::writeBinaryData(): .bt body, octomap_msgs/Octomap binary data
  std::string full_data;    ///< OcTree::writeData(): .ot body (empty unless full_data was asked)
};

/// Encodes the slab of `raster` (resolution and origin as the raster's; the origin must be a
/// multiple of the resolution, as buildOccupancy makes it). Throws InputError if the raster does
/// not fit OctoMap's 2^16 voxels per axis around the origin.
OctomapSlab encodeOctomapSlab(const OccupancyRaster& raster, const OctomapSlabParams& params = {});

/// Walks an OcTree binary stream (OcTree::writeBinaryData: per inner node two bytes of 2-bit child
/// codes, depth first) without building the tree: the number of nodes OcTree::size() would report
/// after readBinaryData, or nullopt if the stream is malformed (truncated, trailing bytes, deeper
/// than OctoMap's 16 levels). Lets a .bt file be checked and written in O(1) extra memory.
std::optional<std::size_t> octreeBinaryNodeCount(std::string_view data);

/// A whole .bt file (OcTree::writeBinaryConst) and .ot file (OcTree::write) of the slab.
std::string octomapBinaryFile(const OctomapSlab& slab);
std::string octomapFullFile(const OctomapSlab& slab);

}  // namespace radarslam
