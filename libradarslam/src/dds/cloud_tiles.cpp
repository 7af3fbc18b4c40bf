// The cloud of a tiled map over DDS (dds/cloud_tiles.h).
#include "radarslam/dds/cloud_tiles.h"

#include <fcntl.h>
#include <unistd.h>

#include "radarslam/core/errors.h"
#include "radarslam/dds/map_messages.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/sha256.h"

namespace radarslam::dds {

namespace fs = std::filesystem;

namespace {

void writeAll(int fd, const void* data, std::size_t n, const fs::path& file) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w <= 0) throw InputError(file.string(), "write failed (disk full or no permission?)");
    p += w, n -= static_cast<std::size_t>(w);
  }
}

bool isOurLayout(const PointCloud2Msg& m) {
  return m.fields == cloudRecordFields() && m.point_step == kCloudRecordBytes && m.height == 1 &&
         !m.is_bigendian && m.data.size() == std::uint64_t{m.width} * kCloudRecordBytes;
}

}  // namespace

PointCloud2Msg cloudTileMessage(const MapInfoMsg& info, std::vector<std::uint8_t> data) {
  return cloudRecordsMessage(info.header, std::move(data));
}

void describeCloudTiles(MapInfoMsg& info, const std::vector<CloudTileEntry>& index, std::uint64_t points,
                        const std::string& data_sha256) {
  info.cloud_tile_count = static_cast<std::uint32_t>(index.size());
  info.cloud_points = index.empty() ? 0 : static_cast<std::uint32_t>(points);
  info.cloud_sha256 = index.empty() ? "" : data_sha256;
}

TiledCloudWriter::TiledCloudWriter(const fs::path& dir, const MapInfoMsg& info)
    : dir_(dir),
      stamp_(info.header.stamp),
      expected_tiles_(info.cloud_tile_count),
      expected_points_(info.cloud_points),
      expected_sha_(info.cloud_sha256),
      sha_(std::make_unique<Sha256>()) {
  if (expected_tiles_ == 0 || expected_sha_.size() != 64)
    throw InputError("MapInfo", "not a consistent description of a tiled cloud");
  tmp_ = dir_ / (".cloud.pcd.tiles-" + std::to_string(::getpid()));
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(tmp_.string(), "cannot create the cloud file");
  const std::string header = cloudPcdHeader(expected_points_);
  writeAll(fd_, header.data(), header.size(), tmp_);
}

TiledCloudWriter::~TiledCloudWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!finished_) ::unlink(tmp_.c_str());  // our own temporary file only
}

bool TiledCloudWriter::add(const PointCloud2Msg& tile) {
  if (!(tile.header.stamp == stamp_)) return false;
  if (!isOurLayout(tile))
    throw InputError("PointCloud2",
                     "cloud tile " + std::to_string(tiles_) +
                         ": expected fields x y z intensity (FLOAT32, point_step 16, height 1)");
  if (tiles_ == expected_tiles_ || tile.width > expected_points_ - points_)
    throw InputError("PointCloud2", "more cloud tiles or points than MapInfo announces (" +
                                        std::to_string(expected_tiles_) + " tiles, " +
                                        std::to_string(expected_points_) + " points)");
  writeAll(fd_, tile.data.data(), tile.data.size(), tmp_);
  sha_->update({tile.data.data(), tile.data.size()});
  points_ += tile.width;
  ++tiles_;
  return true;
}

std::string TiledCloudWriter::finish() {
  if (!complete() || points_ != expected_points_)
    throw InputError(tmp_.string(), "incomplete: " + std::to_string(tiles_) + " of " +
                                        std::to_string(expected_tiles_) + " tiles, " +
                                        std::to_string(points_) + " of " + std::to_string(expected_points_) +
                                        " points");
  const std::string got = sha_->hexDigest();
  if (got != expected_sha_)
    throw InputError(tmp_.string(),
                     "the cloud tiles have SHA-256 " + got + ", MapInfo says " + expected_sha_);
  if (::fsync(fd_) != 0) throw InputError(tmp_.string(), "fsync failed");
  ::close(fd_);
  fd_ = -1;
  fs::rename(tmp_, dir_ / "cloud.pcd");
  finished_ = true;
  return got;
}

}  // namespace radarslam::dds
