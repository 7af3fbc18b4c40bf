// `radarslam map-layers MAP`: (re)builds the published layers (grid, point cloud, OctoMap) of an
// existing map, e.g. one saved by an older radarslam (format version 1), so that
// radarslam-map-server publishes them without building them at every start. The map is saved
// again in the current format with the layers, atomically (map/map_io.h); every other file of the
// map directory (trajectories, exports, evaluation) is carried over as a hard link (or a copy).
#include <chrono>
#include <filesystem>
#include <iostream>
#include <set>
#include <string>

#include <radarslam/core/errors.h>
#include <radarslam/map/layer_files.h>
#include <radarslam/map/map_io.h>

#include "cli_common.h"
#include "command.h"
#include "layer_config.h"

namespace radarslam::cli {
namespace {

namespace fs = std::filesystem;

// Everything in `from` that saveMap does not write itself goes into the new map directory.
void carryOver(const fs::path& from, const fs::path& to) {
  static const std::set<std::string> written_by_save = {"manifest.yaml", "parameters.yaml", "keyframes.bin",
                                                        "points.bin",    "graph.bin",       kLayersDir};
  for (const auto& e : fs::directory_iterator(from)) {
    const std::string name = e.path().filename().string();
    if (written_by_save.count(name)) continue;
    std::error_code ec;
    fs::copy(
        e.path(), to / name,
        fs::copy_options::recursive | fs::copy_options::copy_symlinks | fs::copy_options::create_hard_links,
        ec);
    if (ec) {  // e.g. a file system without hard links
      ec.clear();
      fs::remove_all(to / name, ec);
      fs::copy(e.path(), to / name, fs::copy_options::recursive | fs::copy_options::copy_symlinks, ec);
    }
    if (ec) throw InputError(e.path().string(), "cannot carry it over into the new map: " + ec.message());
  }
}

int runMapLayers(int argc, char** argv) {
  CommandLine cmd("map-layers",
                  "(Re)builds the published layers of a saved map (layers/grid.pgm + grid.yaml, cloud.pcd, "
                  "map.bt, listed with their SHA-256 in manifest.yaml) so radarslam-map-server publishes "
                  "them without loading the keyframes. Use it on maps saved by an older radarslam or to "
                  "change the layer parameters. The map is rewritten atomically in the current format; its "
                  "other files are kept.");
  TCLAP::UnlabeledValueArg<std::string> map_arg("map", "Map name (maps/NAME) or directory", true, "", "MAP",
                                                cmd.tclap());
  TCLAP::ValueArg<std::string> config_arg(
      "", "config",
      "YAML whose map_layers: section sets the layer parameters (default: built-in, "
      "docs/parameters.md)",
      false, "", "FILE", cmd.tclap());
  TCLAP::ValueArg<double> res_arg("", "resolution",
                                  "Grid and OctoMap cell size [m] (0, 100], overrides the configuration",
                                  false, 0.2, "M", cmd.tclap());
  cmd.parse(argc, argv);

  MapLayerParams params = layerParamsFromConfig(config_arg.getValue());
  if (res_arg.isSet()) {
    if (!(res_arg.getValue() > 0 && res_arg.getValue() <= 100))
      throw InputError("radarslam map-layers", "--resolution must be in (0, 100] m");
    params.grid.resolution_m = params.octomap.resolution_m = res_arg.getValue();
  }
  const fs::path dir = resolveMapPath(map_arg.getValue());
  const auto t0 = std::chrono::steady_clock::now();
  const KeyframeMap map = loadMap(dir);  // InputError naming the file if it is not a good map
  MapSaveHooks hooks;
  hooks.write_products = [&](const fs::path& tmp) { carryOver(dir, tmp); };
  saveMap(map, dir, hooks, params);
  const MapManifestSummary saved = readMapManifest(dir);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << dir.string() << ": layers of " << map.keyframes.size() << " keyframes (format "
            << map.meta.format_version << " -> " << saved.format_version << ") in " << secs << " s: grid "
            << saved.layers->grid_width << "x" << saved.layers->grid_height << " at "
            << params.grid.resolution_m << " m, cloud " << saved.layers->cloud_points << " points, octomap "
            << saved.layers->file("octomap").bytes << " bytes\n";
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("map-layers", "(Re)build a saved map's published layers (grid, cloud, OctoMap) in place",
                  runMapLayers);

}  // namespace radarslam::cli
