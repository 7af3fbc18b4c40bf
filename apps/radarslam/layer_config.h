#pragma once
// The map layer parameters of the commands that save maps without a SLAM configuration
// (`map-synth`, `map-layers`): the `map_layers:` section of a --config YAML (a sensor config
// such as config/sim.yaml, whose other sections are validated too), or the built-in defaults.
#include <string>

#include <radarslam/map/map_layers.h>

namespace radarslam::cli {

/// Defaults if `config_path` is empty; throws InputError naming the file and the key otherwise.
MapLayerParams layerParamsFromConfig(const std::string& config_path);

}  // namespace radarslam::cli
