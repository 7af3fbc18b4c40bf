// Point-cloud export: all keyframe points in the map frame as binary PLY and PCD (v0.7). Both
// are written by hand (MRPT has no PCD writer and its PLY writer is ASCII only).
#include <cmath>
#include <cstring>
#include <string>

#include "radarslam/core/atomic_file.h"
#include "radarslam/map/map_exports.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {
// x, y, z, intensity as little-endian float32 (the host is little-endian; see binary_codec.h).
std::string worldPointsXYZI(const KeyframeMap& map, std::size_t& count) {
  count = 0;
  for (const auto& kf : map.keyframes) count += kf.points.size();
  std::string data;
  data.reserve(count * 16);
  for (const auto& kf : map.keyframes) {
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points) {
      const float v[4] = {static_cast<float>(kf.pose.x + c * p.x - s * p.y),
                          static_cast<float>(kf.pose.y + s * p.x + c * p.y), 0.f, p.power};
      data.append(reinterpret_cast<const char*>(v), sizeof v);
    }
  }
  return data;
}
}  // namespace

std::vector<fs::path> exportPointCloud(const KeyframeMap& map, const fs::path& dir, const std::string& stem) {
  std::size_t n = 0;
  const std::string data = worldPointsXYZI(map, n);
  const std::string count = std::to_string(n);

  std::string ply = "ply\nformat binary_little_endian 1.0\ncomment radarslam map points, map frame\n";
  ply.append("element vertex ").append(count).append("\n");
  ply.append("property float x\nproperty float y\nproperty float z\nproperty float intensity\nend_header\n");
  ply.append(data);

  std::string pcd = "# .PCD v0.7 - radarslam map points, map frame\nVERSION 0.7\nFIELDS x y z intensity\n";
  pcd.append("SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH ").append(count);
  pcd.append("\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS ").append(count).append("\nDATA binary\n");
  pcd.append(data);

  const fs::path ply_path = dir / (stem + ".ply"), pcd_path = dir / (stem + ".pcd");
  writeTextAtomically(ply_path, ply);
  writeTextAtomically(pcd_path, pcd);
  return {ply_path, pcd_path};
}

}  // namespace radarslam
