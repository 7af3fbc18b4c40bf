// `radarslam export MAP`: writes a saved map in formats other tools read (occupancy grid as
// PNG/PGM + ROS map_server YAML and MRPT .gridmap, OctoMap .bt/.ot, PLY/PCD point cloud, MRPT
// .simplemap). Prints the written files on stdout, progress on stderr.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <radarslam/core/cleanup_on_signal.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/core/output_path.h>
#include <radarslam/map/map_exports.h>
#include <radarslam/map/map_io.h>

#include "cli_common.h"
#include "command.h"

namespace radarslam::cli {
namespace {

namespace fs = std::filesystem;

/// Moves the staged `files` into `target`: the whole directory at once if `target` does not exist
/// yet, else file by file (replacing files of the same names, keeping the others).
void publishFiles(const fs::path& staging, const fs::path& target, const std::vector<fs::path>& files) {
  std::error_code ec;
  if (!fs::exists(target, ec)) {
    fs::rename(staging, target, ec);
    if (ec) throw InputError(target.string(), "cannot move the exports into place: " + ec.message());
    return;
  }
  for (const auto& f : files) {
    fs::rename(staging / f, target / f, ec);
    if (ec) throw InputError((target / f).string(), "cannot move into place: " + ec.message());
  }
  fs::remove(staging, ec);
}

int runExport(int argc, char** argv) {
  CommandLine cmd(
      "export",
      "Exports a saved map (a name in maps/ or $RADARSLAM_MAPS_DIR, or a path) to an occupancy grid "
      "(PNG/PGM with ROS map_server YAML, MRPT .gridmap), an OctoMap (.bt, .ot), a point cloud "
      "(binary PLY, PCD) and an MRPT .simplemap. Without a format option, exports all of them.");
  TCLAP::UnlabeledValueArg<std::string> map_arg("map", "Map name or directory", true, "", "MAP", cmd.tclap());
  TCLAP::SwitchArg grid_arg("", "grid", "Occupancy grid: grid.png/.pgm (+ .yaml), grid.gridmap", cmd.tclap());
  TCLAP::SwitchArg octo_arg("", "octomap", "OctoMap: map.bt, map.ot", cmd.tclap());
  TCLAP::SwitchArg cloud_arg("", "cloud", "Point cloud: cloud.ply, cloud.pcd", cmd.tclap());
  TCLAP::SwitchArg sm_arg("", "simplemap", "MRPT simple map: map.simplemap", cmd.tclap());
  TCLAP::SwitchArg all_arg("", "all", "All of the above (the default)", cmd.tclap());
  TCLAP::ValueArg<std::string> out_arg(
      "o", "output",
      "Output directory (default MAP/exports); files of the same names are replaced, others kept", false, "",
      "DIR", cmd.tclap());
  TCLAP::ValueArg<double> res_arg("", "resolution", "Grid and OctoMap cell size [m] (default 0.2)", false,
                                  0.2, "M", cmd.tclap());
  cmd.parse(argc, argv);
  if (!(res_arg.getValue() > 0.0) || res_arg.getValue() > 100.0)
    throw InputError("radarslam export", "--resolution must be in (0, 100] m");
  const bool none =
      !grid_arg.getValue() && !octo_arg.getValue() && !cloud_arg.getValue() && !sm_arg.getValue();
  const bool all = all_arg.getValue() || none;

  const fs::path dir = resolveMapPath(map_arg.getValue());
  if (out_arg.isSet()) {  // MAP/exports (the default) is part of the map
    checkNoOverlap(dir, out_arg.getValue(), /*allow_inside=*/true);
    checkDirectoryOutput(out_arg.getValue(), "-o");
  }
  const fs::path out = out_arg.isSet() ? fs::path(out_arg.getValue()) : dir / "exports";
  const auto t0 = std::chrono::steady_clock::now();
  const KeyframeMap map = loadMap(dir);
  const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  logger().logFmt(mrpt::system::LVL_INFO, "loaded %s: %zu keyframes, %zu map points, %zu edges (%.3f s)",
                  dir.string().c_str(), map.keyframes.size(), map.points.size(), map.edges.size(), load_s);

  // All files are made in a hidden sibling of the output directory and moved in at the end: an
  // interrupted or failed export leaves the previous files, not a mix (cleanup_on_signal.h).
  const fs::path target = followSymlinks(out);
  const fs::path staging = stagingSibling(target, "export-tmp");
  const TemporaryPath removed_on_signal(staging);
  std::error_code ec;
  fs::remove_all(staging, ec);
  fs::create_directories(staging, ec);
  if (ec) throw InputError(staging.string(), "cannot create directory: " + ec.message());
  std::vector<fs::path> files;
  try {
    auto step = [&](const char* what, auto&& fn) {
      const auto t = std::chrono::steady_clock::now();
      for (const auto& f : fn()) files.push_back(f.filename());
      logger().logFmt(mrpt::system::LVL_INFO, "%s written (%.2f s)", what,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
    };
    if (all || grid_arg.getValue()) {
      GridExportParams p;
      p.resolution_m = res_arg.getValue();
      step("occupancy grid", [&] { return exportOccupancyGrid(map, staging, "grid", p); });
    }
    if (all || octo_arg.getValue()) {
      OctomapExportParams p;
      p.resolution_m = res_arg.getValue();
      step("octomap", [&] { return exportOctomap(map, staging, "map", p); });
    }
    if (all || cloud_arg.getValue())
      step("point cloud", [&] { return exportPointCloud(map, staging, "cloud"); });
    if (all || sm_arg.getValue()) step("simplemap", [&] { return exportSimpleMap(map, staging, "map"); });
    publishFiles(staging, target, files);
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  for (auto& f : files) f = out / f;
  for (const auto& f : files) std::cout << f.string() << "\n";
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("export", "Export a saved map: occupancy grid, OctoMap, PLY/PCD cloud, MRPT simplemap",
                  runExport);

}  // namespace radarslam::cli
