// `radarslam map-synth DATASET -o MAP`: builds a KeyframeMap from a dataset's ground truth (a
// keyframe every --every metres or 0.2 rad, each with its Algorithm-1 peak cloud) for tests,
// demos and exporter development before SLAM exists. Uses the same insertion code as SLAM.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>

#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/core/output_path.h>
#include <radarslam/core/version.h>
#include <radarslam/io/dataset.h>
#include <radarslam/map/map_from_trajectory.h>
#include <radarslam/map/map_io.h>
#include <radarslam/radar/peak_cloud.h>

#include "cli_common.h"
#include "command.h"
#include "layer_config.h"

namespace radarslam::cli {
namespace {

int runMapSynth(int argc, char** argv) {
  CommandLine cmd(
      "map-synth",
      "Builds a map from a dataset's ground truth: a keyframe every --every metres (or 0.2 rad) with "
      "its peak point cloud (paper Algorithm 1), odometry edges between keyframes. For tests and "
      "demos of the map format and exports; not SLAM.");
  TCLAP::UnlabeledValueArg<std::string> data_arg("dataset", "Dataset directory with ground truth", true, "",
                                                 "DATASET", cmd.tclap());
  TCLAP::ValueArg<std::string> out_arg("o", "output",
                                       "Map name (maps/NAME) or directory; an existing map there is replaced",
                                       true, "", "MAP", cmd.tclap());
  TCLAP::ValueArg<double> every_arg("", "every", "Keyframe distance [m] (default 2)", false, 2.0, "M",
                                    cmd.tclap());
  TCLAP::ValueArg<unsigned> max_arg("", "max-keyframes", "Stop after this many keyframes (0 = all)", false, 0,
                                    "N", cmd.tclap());
  TCLAP::SwitchArg force_arg("", "force",
                             "Let -o replace an empty directory or a regular file (a map is always "
                             "replaced; a non-empty directory that is not a map never is)",
                             cmd.tclap());
  TCLAP::ValueArg<std::string> config_arg(
      "", "config",
      "YAML whose map_layers: section sets the parameters of the layers saved with the map "
      "(default: built-in, docs/parameters.md)",
      false, "", "FILE", cmd.tclap());
  cmd.parse(argc, argv);
  const MapLayerParams layer_params = layerParamsFromConfig(config_arg.getValue());
  if (!(every_arg.getValue() > 0.0 && every_arg.getValue() <= 1e4))
    throw InputError("radarslam map-synth", "--every must be in (0, 10000] m");
  if (out_arg.getValue().empty()) throw InputError("-o", "empty output path");
  const auto dir = resolveMapPath(out_arg.getValue());
  checkNoOverlap(data_arg.getValue(), dir);
  checkMapOutput(dir, force_arg.getValue());

  const auto reader = openDataset(data_arg.getValue());
  if (!reader->hasGroundTruth())
    throw InputError(data_arg.getValue(),
                     "no ground truth: map-synth places keyframes at ground-truth poses");
  KeyframeInsertionParams kp;
  kp.keyframe_distance_m = every_arg.getValue();
  const PeakCloudParams pp;
  KeyframeMap map;
  map.meta.source_dataset = std::filesystem::absolute(data_arg.getValue()).lexically_normal().string();
  map.meta.software_version = radarslam::versionText();
  map.meta.clouds_motion_compensated = false;  // raw sweeps: the localiser compensates them
  map.meta.parameters_yaml =
      "map_synth:\n  keyframe_distance_m: " + std::to_string(kp.keyframe_distance_m) +
      "\n  keyframe_angle_rad: " + std::to_string(kp.keyframe_angle_rad) +
      "\npeak_cloud:\n  min_peak_prominence: " + std::to_string(pp.min_peak_prominence) +
      "\n  min_peak_distance_bins: " + std::to_string(pp.min_peak_distance_bins) +
      "\n  min_range_m: " + std::to_string(pp.min_range_m) + "\n";

  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = reader->size();
  std::size_t next_report = n / 10;
  for (std::size_t i = 0; i < n; ++i) {
    if (max_arg.getValue() > 0 && map.keyframes.size() >= max_arg.getValue()) break;
    const auto gt = reader->groundTruthAt(reader->indexStamp(i));
    if (!gt || !needsKeyframe(map, *gt, kp)) continue;
    CObservationRadarScan::Ptr scan;
    try {
      scan = reader->readScan(i);
    } catch (const InputError& e) {
      logger().logFmt(mrpt::system::LVL_WARN, "skipping scan %zu: %s", i, e.what());
      continue;
    }
    const auto pose = reader->groundTruthAt(scan->refStampNs());
    if (!pose) continue;
    if (map.keyframes.empty()) {
      map.meta.sensor = {static_cast<std::uint32_t>(scan->num_azimuths),
                         static_cast<std::uint32_t>(scan->num_bins), scan->range_resolution_m,
                         scan->range_offset_m};
    }
    addKeyframe(map, scan->refStampNs(), *pose, extractPeakCloud(*scan, pp), {}, kp);
    if (i >= next_report) {
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double rate = static_cast<double>(i + 1) / el;
      logger().logFmt(mrpt::system::LVL_INFO, "scan %zu/%zu, %zu keyframes, %.0f scans/s, ETA %.0f s", i + 1,
                      n, map.keyframes.size(), rate, static_cast<double>(n - i - 1) / rate);
      next_report += n / 10 + 1;
    }
  }
  if (map.keyframes.empty())
    throw InputError(data_arg.getValue(), "no keyframe: no scan has a ground-truth pose");
  saveMap(map, dir, {}, layer_params);
  std::size_t points = 0;
  for (const auto& kf : map.keyframes) points += kf.points.size();
  std::cout << dir.string() << ": " << map.keyframes.size() << " keyframes, " << points << " points\n";
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("map-synth", "Build a map from a dataset's ground truth (for tests and demos)",
                  runMapSynth);

}  // namespace radarslam::cli
