// OctoMap export. Default (Fill::grid_columns): the occupancy raster lifted into the slab
// z in [0, resolution), encoded directly (octomap_slab.h). Fill::point_rays: the keyframe points at
// z = 0 inserted per keyframe from its origin (octomap::OcTree::insertPointCloud), written through
// the stream API into memory. Both are written atomically, nothing is printed to our stdout.
#include <octomap/OcTree.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/map/map_exports.h"
#include "radarslam/map/octomap_slab.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> writeGridColumns(const KeyframeMap& map, const fs::path& dir, const std::string& stem,
                                       const OctomapExportParams& params) {
  GridExportParams grid;
  grid.resolution_m = params.resolution_m;
  const OctomapSlab slab = encodeOctomapSlab(buildOccupancy(map, grid));
  const fs::path bt = dir / (stem + ".bt"), ot = dir / (stem + ".ot");
  writeTextAtomically(bt, octomapBinaryFile(slab));
  writeTextAtomically(ot, octomapFullFile(slab));
  return {bt, ot};
}

struct Box {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  void grow(double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  double cells(double res) const {
    return x1 < x0 ? 0.0 : (std::floor((x1 - x0) / res) + 1) * (std::floor((y1 - y0) / res) + 1);
  }
};

/// Refuses resolutions whose tree would not fit: the voxels the rays touch are at most the
/// smaller of the whole map's box and the sum of the keyframes' boxes, in voxels.
void checkTreeSize(const KeyframeMap& map, const OctomapExportParams& params) {
  const double res = params.resolution_m;
  Box all;
  double sum = 0.0;
  for (const auto& kf : map.keyframes) {
    Box b;
    b.grow(kf.pose.x, kf.pose.y);
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points) b.grow(kf.pose.x + c * p.x - s * p.y, kf.pose.y + s * p.x + c * p.y);
    sum += b.cells(res);
    all.grow(b.x0, b.y0), all.grow(b.x1, b.y1);
  }
  const double reach = std::max({std::abs(all.x0), std::abs(all.x1), std::abs(all.y0), std::abs(all.y1)});
  if (!map.keyframes.empty() && reach / res >= 32767)
    throw InputError("octomap export", "points " + std::to_string(static_cast<long long>(reach)) +
                                           " m from the origin need more than 32767 voxels of " +
                                           std::to_string(res) + " m; use a coarser --resolution");
  const double voxels = std::min(sum, all.cells(res));
  if (voxels > static_cast<double>(params.max_voxels))
    throw InputError("octomap export", "an OctoMap of about " +
                                           std::to_string(static_cast<long long>(voxels)) +
                                           " voxels (limit " + std::to_string(params.max_voxels) +
                                           ") is too large; use a coarser --resolution");
}
}  // namespace

std::vector<fs::path> exportOctomap(const KeyframeMap& map, const fs::path& dir, const std::string& stem,
                                    const OctomapExportParams& params) {
  if (!(params.resolution_m > 0)) throw InputError("octomap export", "resolution must be > 0");
  if (params.fill == OctomapExportParams::Fill::grid_columns) return writeGridColumns(map, dir, stem, params);
  checkTreeSize(map, params);
  octomap::OcTree tree(params.resolution_m);
  // Ray tracing is slow (about 0.14 s per 1500-point keyframe): report progress with rate and ETA.
  const auto t0 = std::chrono::steady_clock::now();
  auto last_report = t0;
  const std::size_t n = map.keyframes.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Keyframe& kf = map.keyframes[k];
    const auto now = std::chrono::steady_clock::now();
    if (now - last_report > std::chrono::seconds(5)) {  // every 5 s
      last_report = now;
      const double rate = static_cast<double>(k) / std::chrono::duration<double>(now - t0).count();
      logger().logFmt(mrpt::system::LVL_INFO, "octomap: keyframe %zu/%zu, %.1f keyframes/s, ETA %.0f s", k, n,
                      rate, static_cast<double>(n - k) / rate);
    }
    octomap::Pointcloud cloud;
    cloud.reserve(kf.points.size());
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points)
      cloud.push_back(static_cast<float>(kf.pose.x + c * p.x - s * p.y),
                      static_cast<float>(kf.pose.y + s * p.x + c * p.y), 0.f);
    // lazy_eval: inner nodes are updated once at the end; discretize: one ray per end voxel.
    tree.insertPointCloud(cloud,
                          octomap::point3d(static_cast<float>(kf.pose.x), static_cast<float>(kf.pose.y), 0.f),
                          params.max_range_m, /*lazy_eval=*/true, /*discretize=*/true);
  }
  tree.updateInnerOccupancy();
  std::vector<fs::path> files;
  auto write = [&](const std::string& ext, bool binary) {
    const fs::path path = dir / (stem + ext);
    std::ostringstream os(std::ios::binary);
    const bool ok = binary ? tree.writeBinaryConst(os) : tree.write(os);
    if (!ok) throw InputError(path.string(), "OctoMap serialisation failed");
    writeTextAtomically(path, os.str());
    files.push_back(path);
  };
  write(".bt", true);
  write(".ot", false);
  return files;
}

}  // namespace radarslam
