#include "layer_config.h"

#include <radarslam/core/input_file.h>
#include <radarslam/core/yaml_params.h>
#include <radarslam/slam/slam_params.h>

namespace radarslam::cli {

MapLayerParams layerParamsFromConfig(const std::string& config_path) {
  if (config_path.empty()) return {};
  requireRegularFile(config_path);
  const YamlParams yaml = YamlParams::fromFile(config_path);
  SlamParams all;  // a sensor config holds the SLAM sections as well: validate the whole file
  loadParams(yaml, all);
  yaml.rejectUnknownKeys();
  return all.map_layers;
}

}  // namespace radarslam::cli
