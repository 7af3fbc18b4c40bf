// `radarslam info PATH`: what a dataset directory (or .rawlog) holds: kind, sensor, scan count,
// duration, geometry (from the first readable scan), ground truth and its length.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <radarslam/core/errors.h>
#include <radarslam/core/trajectory.h>
#include <radarslam/io/dataset.h>

#include "cli_common.h"
#include "command.h"

namespace radarslam::cli {
namespace {

// Which optional file would have held the ground truth, and what its absence disables.
std::string missingGroundTruth(DatasetKind kind) {
  const char* file = nullptr;
  switch (kind) {
    case DatasetKind::Oxford:
      file = "gt/radar_odometry.csv";
      break;
    case DatasetKind::MulRanOxfordForm:
    case DatasetKind::MulRanPolar:
      file = "global_pose.csv";
      break;
    case DatasetKind::Boreas:
      file = "applanix/radar_poses.csv";
      break;
    case DatasetKind::Radiate:
    case DatasetKind::Rawlog:
      return " (this layout carries none)";
  }
  return std::string(" (") + file +
         " missing: odometry, map and localize run, but evaluate nothing; map-synth needs it)";
}

int runInfo(int argc, char** argv) {
  CommandLine cmd("info",
                  "Describes a radar dataset directory or .rawlog: dataset kind, sensor, number of scans, "
                  "duration, scan geometry (decoded from the first readable scan) and ground truth.");
  TCLAP::UnlabeledValueArg<std::string> path_arg("path", "Dataset directory or .rawlog file", true, "",
                                                 "PATH", cmd.tclap());
  TCLAP::ValueArg<double> res_arg("", "range-resolution", "Override the range resolution [m/bin]", false, 0.0,
                                  "M", cmd.tclap());
  TCLAP::ValueArg<double> offset_arg("", "range-offset", "Override the range of bin 0 [m]", false, 0.0, "M",
                                     cmd.tclap());
  TCLAP::SwitchArg check_arg("", "check", "Decode and check every scan (slow on long sequences)",
                             cmd.tclap());
  TCLAP::SwitchArg skip_arg("", "skip-bad-scans",
                            "With --check: report bad scans and continue instead of failing", cmd.tclap());
  cmd.parse(argc, argv);
  if (res_arg.isSet() && !(res_arg.getValue() > 0.0))
    throw InputError("radarslam info", "--range-resolution must be > 0");

  ReaderOptions options;
  options.range_resolution_m = res_arg.getValue();
  if (offset_arg.isSet()) options.range_offset_m = offset_arg.getValue();
  const std::filesystem::path path = path_arg.getValue();
  const auto reader = openDataset(path, options);

  std::cout << "path:          " << path.string() << "\n"
            << "dataset:       " << toString(reader->kind()) << "\n"
            << "sensor:        " << reader->sensorName() << "\n"
            << "scans:         " << reader->size() << "\n";
  const double duration = toSeconds(reader->indexStamp(reader->size() - 1) - reader->indexStamp(0));
  std::cout << "duration:      " << formatText("%.3f", duration) << " s (first to last scan stamp)\n";

  // Geometry from the first scan that decodes (a sequence may list scans that are missing).
  CObservationRadarScan::Ptr scan;
  std::size_t first_ok = 0;
  std::optional<std::string> first_error;
  for (; first_ok < reader->size() && !scan; ++first_ok) {
    try {
      scan = reader->readScan(first_ok);
    } catch (const InputError& e) {
      if (!first_error) first_error = e.what();
    }
  }
  if (!scan)
    throw InputError(path.string(), "no scan could be decoded; first error: " + first_error.value_or("?"));
  --first_ok;
  std::cout << "geometry:      " << scan->num_azimuths << " azimuths x " << scan->num_bins << " bins, "
            << formatText("%.6g", scan->range_resolution_m) << " m/bin, range offset "
            << formatText("%.6g", scan->range_offset_m) << " m, max range "
            << formatText("%.1f", scan->maxRange()) << " m\n"
            << "sweep:         "
            << formatText("%.1f",
                          toSeconds(scan->azimuth_stamps_ns.back() - scan->azimuth_stamps_ns.front()) * 1e3)
            << " ms first to last azimuth (scan " << first_ok << ": "
            << reader->scanPath(first_ok).filename().string() << ")\n";
  if (scan->hasChirpDirections()) {
    const auto up = std::count(scan->azimuth_chirp.begin(), scan->azimuth_chirp.end(), std::int8_t{1});
    std::cout << "chirp:         " << up << " up / " << scan->num_azimuths - up
              << " down-chirp azimuths (per-azimuth chirp flag: Doppler range offsets of opposite signs)\n";
  }
  if (first_ok > 0)
    std::cout << "warning:       " << first_ok
              << " scan(s) before it could not be read; first: " << *first_error << "\n";

  if (reader->hasGroundTruth()) {
    const auto& gt = reader->groundTruth();
    std::cout << "ground truth:  yes, " << gt.size() << " poses over "
              << formatText("%.1f", toSeconds(gt.back().stamp - gt.front().stamp)) << " s, path length "
              << formatText("%.3f", pathLength(gt) / 1000.0) << " km\n";
  } else {
    std::cout << "ground truth:  no" << missingGroundTruth(reader->kind()) << "\n";
  }
  for (const std::string& part : reader->missingParts()) std::cout << "missing:       " << part << "\n";

  if (check_arg.getValue()) {
    ScanIterator it(*reader, skip_arg.getValue());
    std::size_t good = 0;
    while (it.next()) ++good;
    std::cout << "check:         " << good << " good scans, " << it.skipped() << " bad (skipped)\n";
  }
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("info", "Describe a radar dataset or .rawlog (kind, scans, geometry, ground truth)",
                  runInfo);

}  // namespace radarslam::cli
