// OctoMap export. Default (Fill::grid_columns): the occupancy raster lifted into the slab
// z in [0, resolution), encoded directly (octomap_slab.h). Fill::point_rays: the keyframe points at
// z = 0 inserted per keyframe from its origin (octomap::OcTree::insertPointCloud), written through
// the stream API into memory. Both are written atomically, nothing is printed to our stdout.
#include <octomap/OcTree.h>

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

}  // namespace

std::vector<fs::path> exportOctomap(const KeyframeMap& map, const fs::path& dir, const std::string& stem,
                                    const OctomapExportParams& params) {
  if (!(params.resolution_m > 0)) throw InputError("octomap export", "resolution must be > 0");
  if (params.fill == OctomapExportParams::Fill::grid_columns) return writeGridColumns(map, dir, stem, params);
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
