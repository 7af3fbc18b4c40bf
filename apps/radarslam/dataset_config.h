#pragma once
// Shared by the commands that run the pipeline: the default parameter file for a dataset kind
// (config/<sensor>.yaml), where its ground truth comes from, and the progress clock format.
#include <filesystem>
#include <optional>
#include <string>

#include <radarslam/io/dataset.h>

namespace radarslam::cli {

/// config/<sensor>.yaml name for a dataset kind ("" for none, e.g. a rawlog).
std::string defaultConfigName(DatasetKind kind);

/// The parameter file to use: `explicit_path` if given, else config/<name> from
/// $RADARSLAM_CONFIG_DIR, else the first `config` folder walking up from the executable (build
/// trees live inside the source tree), else none (built-in defaults).
std::optional<std::filesystem::path> findConfig(const std::string& explicit_path, DatasetKind kind);

/// config/<name> found as findConfig finds a default (none for an empty name or no such file).
std::optional<std::filesystem::path> findConfigFile(const std::string& name);

/// The file a dataset's ground truth is read from, for messages (gt/radar_odometry.csv,
/// global_pose.csv, applanix/radar_poses.csv; the .rawlog itself).
std::filesystem::path groundTruthFile(const DatasetReader& reader);

/// "m:ss"
std::string clockText(double seconds);

}  // namespace radarslam::cli
