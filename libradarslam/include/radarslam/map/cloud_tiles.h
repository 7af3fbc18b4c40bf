#pragma once
// The point cloud of a map whose grid is tiled (map/grid_tiles.h), cut along the same tiles
// (docs/dds.md, "Tiled grids"): layers/cloud.pcd holds the points sorted by tile (row of tiles by
// row, west to east; within a tile in keyframe order), layers/cloud_tiles.txt says where each
// tile's points are, and the map server sends each tile as one sensor_msgs/PointCloud2.
#include <cstdint>
#include <string>
#include <vector>

#include "radarslam/map/grid_tiles.h"
#include "radarslam/map/keyframe_map.h"

namespace radarslam {

/// One tile's points: [first, first + count) of the cloud, and the SHA-256 of their 16-byte records.
struct CloudTileEntry {
  std::uint32_t tx = 0, ty = 0;
  std::uint64_t first = 0, count = 0;
  std::string sha256;
  bool operator==(const CloudTileEntry&) const = default;
};

/// Tile key (tiling.tileKey) of a point in the map frame; points outside the grid go to the
/// nearest tile (the grid holds every point with a margin, so this only guards rounding).
std::uint32_t cloudTileKey(const GridTiling& tiling, double resolution, double origin_x, double origin_y,
                           float x, float y);

/// The cloud payload (cloudPayload's 16-byte records x y z intensity) already sorted by tile,
/// stably (within a tile in keyframe order), and the index of the tiles holding points. Written
/// in place in two passes over the keyframes: no second copy of the payload.
struct TiledCloud {
  std::vector<std::uint8_t> data;
  std::vector<CloudTileEntry> tiles;
};
TiledCloud tiledCloudPayload(const KeyframeMap& map, const GridTiling& tiling, double resolution,
                             double origin_x, double origin_y);

/// layers/cloud_tiles.txt after its first line: "tx ty first count sha256" per tile, in order.
std::string cloudTileIndexText(const std::vector<CloudTileEntry>& tiles);
/// Parses and checks (tiles in range and ascending, ranges contiguous from 0 and covering exactly
/// `points`, 64 hex digits); throws InputError(origin) naming the line.
std::vector<CloudTileEntry> parseCloudTileIndex(const std::string& text, const GridTiling& tiling,
                                                std::uint64_t points, const std::string& origin);

}  // namespace radarslam
