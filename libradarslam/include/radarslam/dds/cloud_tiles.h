#pragma once
// The cloud of a tiled map over DDS (docs/dds.md, "Tiled grids"): one sensor_msgs/PointCloud2 per
// tile on rt/radarslam/cloud_map_tiles, in tile order, and a receiver that appends them to
// OUT/cloud.pcd as they arrive (one tile in memory at a time).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "radarslam/dds/messages.h"
#include "radarslam/map/cloud_tiles.h"

namespace radarslam {
class Sha256;
}

namespace radarslam::dds {

/// The points of one tile (16-byte records x y z intensity) as a PointCloud2 of publication `info`.
PointCloud2Msg cloudTileMessage(const MapInfoMsg& info, std::vector<std::uint8_t> data);

/// Fills MapInfo's cloud fields (cloud_tile_count 0 for an untiled cloud).
void describeCloudTiles(MapInfoMsg& info, const std::vector<CloudTileEntry>& index, std::uint64_t points,
                        const std::string& data_sha256);

/// Writes OUT/cloud.pcd of a tiled cloud: the PCD header for MapInfo.cloud_points, then each tile's
/// points appended as it arrives; finish() checks the point count and the SHA-256 against MapInfo
/// and renames the file into place (atomically). A writer destroyed before finish() removes its
/// temporary file; nothing else is touched.
class TiledCloudWriter {
 public:
  /// Throws InputError if `info` does not describe a tiled cloud or the file cannot be created.
  TiledCloudWriter(const std::filesystem::path& dir, const MapInfoMsg& info);
  ~TiledCloudWriter();
  TiledCloudWriter(const TiledCloudWriter&) = delete;
  TiledCloudWriter& operator=(const TiledCloudWriter&) = delete;

  /// True if the tile was appended; false if it belongs to another publication. Throws InputError
  /// for a tile of this publication that is malformed or one too many.
  bool add(const PointCloud2Msg& tile);
  bool complete() const { return tiles_ == expected_tiles_; }
  /// Checks and renames; returns the data's SHA-256. Throws InputError if incomplete or different.
  std::string finish();

 private:
  std::filesystem::path dir_, tmp_;
  int fd_ = -1;
  TimeMsg stamp_;
  std::uint32_t expected_tiles_ = 0, tiles_ = 0;
  std::uint64_t expected_points_ = 0, points_ = 0;
  std::string expected_sha_;
  std::unique_ptr<Sha256> sha_;
  bool finished_ = false;
};

}  // namespace radarslam::dds
