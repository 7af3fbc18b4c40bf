// Point-cloud export: all keyframe points in the map frame as binary PLY and PCD (v0.7). Both
// are written by hand (MRPT has no PCD writer and its PLY writer is ASCII only).
#include <string>
#include <string_view>

#include "radarslam/core/atomic_file.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/map_exports.h"

namespace radarslam {
namespace fs = std::filesystem;

std::vector<fs::path> exportPointCloud(const KeyframeMap& map, const fs::path& dir, const std::string& stem) {
  // The cloud layer's records (map/layer_files.h: x, y, z, intensity as little-endian float32).
  const std::vector<std::uint8_t> payload = cloudPayload(map);
  const std::string_view data(reinterpret_cast<const char*>(payload.data()), payload.size());
  const std::size_t points = payload.size() / kCloudRecordBytes;
  const std::string count = std::to_string(points);

  std::string ply = "ply\nformat binary_little_endian 1.0\ncomment radarslam map points, map frame\n";
  ply.append("element vertex ").append(count).append("\n");
  ply.append("property float x\nproperty float y\nproperty float z\nproperty float intensity\nend_header\n");
  ply.append(data);

  std::string pcd = cloudPcdHeader(points);
  pcd.append(data);

  const fs::path ply_path = dir / (stem + ".ply"), pcd_path = dir / (stem + ".pcd");
  writeTextAtomically(ply_path, ply);
  writeTextAtomically(pcd_path, pcd);
  return {ply_path, pcd_path};
}

}  // namespace radarslam
