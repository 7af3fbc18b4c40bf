// `radarslam eval EST GT`: scores an estimated trajectory against ground truth as radar-SLAM papers
// do (KITTI odometry metric, ATE after SE(2) alignment, frame-to-frame RPE); prints a summary and
// optionally writes a JSON report and plots. GT is a TUM/KITTI file or any supported dataset dir.
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/core/output_path.h>
#include <radarslam/eval/evaluate.h>
#include <radarslam/eval/plots.h>
#include <radarslam/eval/report.h>
#include <radarslam/io/dataset.h>
#include <radarslam/io/trajectory_files.h>

#include "cli_common.h"
#include "command.h"
#include "eval_localization.h"

namespace radarslam::cli {
namespace {

namespace fs = std::filesystem;

std::vector<double> parseLengths(const std::string& text, const std::string& where) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !(v > 0 && v <= 1e5) || out.size() >= 100)
      throw InputError(
          where,
          std::string("--lengths: expected at most 100 numbers in (0, 100000] separated by commas, got '") +
              text + "'");
    out.push_back(v);
  }
  if (out.empty()) throw InputError(where, "--lengths is empty");
  return out;
}

Trajectory loadGroundTruth(const fs::path& path, const TrajectoryReadOptions& options) {
  if (!fs::is_directory(path)) return readTrajectoryFile(path, options);
  const auto reader = openDataset(path);
  if (!reader->hasGroundTruth())
    throw InputError(path.string(),
                     std::string("the ") + toString(reader->kind()) + " dataset has no ground truth");
  return reader->groundTruth();
}

int runEval(int argc, char** argv) {
  CommandLine cmd(
      "eval",
      "Scores an estimated trajectory EST against ground truth GT: KITTI odometry metric "
      "(translational % and rotational deg/100 m over 100..800 m segments), ATE RMSE after SE(2) "
      "alignment, and frame-to-frame RPE. EST is a TUM or KITTI trajectory file; GT is one too, or "
      "a dataset directory whose ground truth is used. GT is interpolated at EST's stamps; "
      "estimates outside GT's time span are dropped and counted. See docs/evaluation.md.");
  TCLAP::UnlabeledValueArg<std::string> est_arg("est", "Estimated trajectory (TUM or KITTI file)", true, "",
                                                "EST", cmd.tclap());
  TCLAP::UnlabeledValueArg<std::string> gt_arg("gt", "Ground truth: TUM/KITTI file or dataset directory",
                                               true, "", "GT", cmd.tclap());
  TCLAP::ValueArg<std::string> json_arg("", "json", "Write the full report as JSON to this file", false, "",
                                        "FILE", cmd.tclap());
  TCLAP::ValueArg<std::string> plot_arg("", "plot-dir",
                                        "Write trajectory and segment-error plots (SVG and PNG) here", false,
                                        "", "DIR", cmd.tclap());
  TCLAP::ValueArg<std::string> est_format_arg("", "est-format", "EST format: auto, tum or kitti", false,
                                              "auto", "FORMAT", cmd.tclap());
  TCLAP::ValueArg<std::string> gt_format_arg("", "gt-format", "GT file format: auto, tum or kitti", false,
                                             "auto", "FORMAT", cmd.tclap());
  TCLAP::ValueArg<std::string> est_stamps_arg("", "est-stamps",
                                              "Stamps for a KITTI EST, one per line (default: EST's "
                                              "<stem>.times.txt if present, else the line index in seconds)",
                                              false, "", "FILE", cmd.tclap());
  TCLAP::ValueArg<std::string> gt_stamps_arg("", "gt-stamps", "Stamps for a KITTI GT file, one per line",
                                             false, "", "FILE", cmd.tclap());
  const eval::EvalParams defaults;
  TCLAP::ValueArg<unsigned> step_arg("", "step",
                                     "KITTI metric: start a segment every N frames (devkit: 10 at 10 Hz; "
                                     "default 4 = one per second at a radar's 4 Hz)",
                                     false, defaults.kitti.step_frames, "N", cmd.tclap());
  TCLAP::ValueArg<std::string> lengths_arg("", "lengths", "KITTI segment lengths in metres", false,
                                           "100,200,300,400,500,600,700,800", "L1,L2,...", cmd.tclap());
  TCLAP::ValueArg<double> gap_arg("", "max-gt-gap",
                                  "Drop estimates between ground-truth poses further apart than this (s)",
                                  false, defaults.max_gt_gap_s, "SECONDS", cmd.tclap());
  TCLAP::SwitchArg localization_arg(
      "", "localization",
      "EST is the per-scan side file of `radarslam localize` (FILE.csv) and GT a trajectory in the map "
      "frame (e.g. a simulated DIR/gt/poses.tum): RMSE of x, y, yaw, NEES consistency, per-status errors",
      cmd.tclap());
  cmd.parse(argc, argv);

  const std::string where = "radarslam eval";
  eval::EvalParams params;
  params.kitti.step_frames = step_arg.getValue();
  params.kitti.lengths_m = parseLengths(lengths_arg.getValue(), where);
  params.max_gt_gap_s = gap_arg.getValue();
  if (params.kitti.step_frames == 0 || params.kitti.step_frames > 1000000)
    throw InputError(where, "--step must be in 1..1000000");
  if (!(params.max_gt_gap_s > 0 && params.max_gt_gap_s <= 1e6))
    throw InputError(where, "--max-gt-gap must be in (0, 1000000] s");

  const fs::path est_path = est_arg.getValue(), gt_path = gt_arg.getValue();
  TrajectoryReadOptions est_options, gt_options;
  est_options.format = parseTrajectoryFormat(est_format_arg.getValue(), where + " --est-format");
  gt_options.format = parseTrajectoryFormat(gt_format_arg.getValue(), where + " --gt-format");
  if (est_stamps_arg.isSet()) est_options.stamps_file = fs::path(est_stamps_arg.getValue());
  if (gt_stamps_arg.isSet()) gt_options.stamps_file = fs::path(gt_stamps_arg.getValue());
  if (fs::is_directory(est_path))
    throw InputError(est_path.string(), "EST must be a trajectory file, not a directory");
  if (fs::is_directory(gt_path) && (gt_format_arg.isSet() || gt_stamps_arg.isSet()))
    throw InputError(where, "--gt-format/--gt-stamps apply to a GT file, not to a dataset directory");

  if (json_arg.isSet()) {
    checkNoOverlap(est_path, json_arg.getValue());
    checkNoOverlap(gt_path, json_arg.getValue());
    checkFileOutput(json_arg.getValue(), "--json");
  }
  if (plot_arg.isSet()) {
    checkNoOverlap(est_path, plot_arg.getValue());
    checkNoOverlap(gt_path, plot_arg.getValue());
    checkDirectoryOutput(plot_arg.getValue(), "--plot-dir");
  }

  if (localization_arg.getValue()) {
    const LocalizationScore score = scoreLocalization(est_path, loadGroundTruth(gt_path, gt_options));
    std::cout << formatLocalizationScore(score);
    if (json_arg.isSet()) {
      writeTextAtomically(json_arg.getValue(),
                          localizationScoreJson(score, est_path.string(), gt_path.string()));
      std::cout << "  report         " << json_arg.getValue() << "\n";
    }
    return 0;
  }
  const Trajectory est = readTrajectoryFile(est_path, est_options);
  const Trajectory gt = loadGroundTruth(gt_path, gt_options);
  const eval::EvalReport report = eval::evaluate(est, gt, params, est_path.string(), gt_path.string());

  std::cout << eval::formatSummary(report);
  if (json_arg.isSet()) {
    eval::writeJsonReport(json_arg.getValue(), report);
    std::cout << "  report         " << json_arg.getValue() << "\n";
  }
  if (plot_arg.isSet()) {
    const auto files = eval::writePlots(plot_arg.getValue(), report);
    std::cout << "  plots         ";
    for (const auto& f : files) std::cout << " " << f.string();
    std::cout << "\n";
  }
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("eval", "Score an estimated trajectory against ground truth (KITTI %, ATE, RPE, plots)",
                  runEval);

}  // namespace radarslam::cli
