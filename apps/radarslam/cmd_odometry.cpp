// `radarslam odometry DIR -o traj.tum`: RadarSLAM pose tracking (front end only) over a dataset,
// writing the trajectory (TUM) and, when the dataset has ground truth, scoring it with the
// evaluation toolkit. Ground truth is never needed to run.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/input_file.h>
#include <radarslam/core/log.h>
#include <radarslam/core/output_path.h>
#include <radarslam/core/yaml_params.h>
#include <radarslam/eval/evaluate.h>
#include <radarslam/eval/plots.h>
#include <radarslam/eval/report.h>
#include <radarslam/frontend/odometry.h>
#include <radarslam/io/dataset.h>
#include <radarslam/io/trajectory_files.h>
#include <radarslam/slam/slam_params.h>

#include "cli_common.h"
#include "command.h"
#include "dataset_config.h"
#include "odometry_steps.h"
#include "progress_line.h"

namespace radarslam::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

int runOdometry(int argc, char** argv) {
  CommandLine cmd(
      "odometry",
      "RadarSLAM pose tracking (paper Sec. III-A) over a radar dataset: keypoints, motion-prior "
      "matching, consistency graph + maximum clique, SVD pose, refinement, keyframes, motion "
      "compensation. Writes the radar pose at every scan's reference time as a TUM trajectory. "
      "With ground truth in the dataset it also prints the KITTI/ATE/RPE metrics. See docs/odometry.md.");
  TCLAP::UnlabeledValueArg<std::string> dir_arg(
      "dataset", "Dataset directory (any supported layout) or .rawlog", true, "", "DIR", cmd.tclap());
  TCLAP::ValueArg<std::string> out_arg(
      "o", "output", "Output trajectory (TUM); a regular file there is replaced, a device or FIFO written to",
      true, "", "FILE", cmd.tclap());
  TCLAP::ValueArg<std::string> config_arg("", "config",
                                          "Parameters (YAML; default: config/<sensor>.yaml for the detected "
                                          "dataset kind, or built-in defaults)",
                                          false, "", "FILE", cmd.tclap());
  TCLAP::SwitchArg skip_arg("", "skip-bad-scans", "Skip (with a warning) scans that cannot be read",
                            cmd.tclap());
  TCLAP::ValueArg<long long> first_arg("", "first", "First scan index (0-based)", false, 0, "N", cmd.tclap());
  TCLAP::ValueArg<long long> count_arg("", "count", "Number of scans (default: to the end)", false, -1, "N",
                                       cmd.tclap());
  TCLAP::ValueArg<std::string> eval_arg(
      "", "eval-dir", "With ground truth: write the evaluation report (JSON) and plots here", false, "",
      "DIR", cmd.tclap());
  TCLAP::ValueArg<std::string> steps_arg(
      "", "steps",
      "Per-scan diagnostics (CSV): status, matches, inliers, search radius, predicted and estimated motion, "
      "stage time; with ground truth also the true motion and whether it lay outside the search radius",
      false, "", "FILE", cmd.tclap());
  TCLAP::SwitchArg quiet_arg("q", "quiet", "No progress line", cmd.tclap());
  cmd.parse(argc, argv);

  const std::string where = "radarslam odometry";
  if (first_arg.getValue() < 0) throw InputError(where, "--first must be >= 0");
  if (count_arg.isSet() && count_arg.getValue() < 1) throw InputError(where, "--count must be >= 1");
  const fs::path dir = dir_arg.getValue(), out = out_arg.getValue();
  if (!fs::exists(dir)) throw InputError(dir.string(), "no such file or directory");
  checkNoOverlap(dir, out);
  checkFileOutput(out);
  if (steps_arg.isSet()) {
    checkNoOverlap(dir, steps_arg.getValue());
    checkFileOutput(steps_arg.getValue());
    checkDistinctOutputs(out, steps_arg.getValue(), "--steps");
  }
  if (eval_arg.isSet()) {
    checkNoOverlap(dir, eval_arg.getValue());
    checkDirectoryOutput(eval_arg.getValue(), "--eval-dir");
  }

  const auto reader = openDataset(dir);
  OdometryParams params;
  std::string config_used = "built-in defaults";
  const std::optional<fs::path> config = findConfig(config_arg.getValue(), reader->kind());
  if (config) {
    requireRegularFile(config->string());
    const YamlParams yaml = YamlParams::fromFile(config->string());
    // The whole parameter set is validated (a config file also holds the slam: section).
    SlamParams all;
    loadParams(yaml, all);
    params = all.odometry;
    yaml.rejectUnknownKeys();
    config_used = config->string();
  }

  const std::size_t first = static_cast<std::size_t>(first_arg.getValue());
  if (first >= reader->size())
    throw InputError(dir.string(), "--first " + std::to_string(first) + " is beyond the last scan (" +
                                       std::to_string(reader->size()) + " scans)");
  const std::size_t end =
      count_arg.isSet() ? std::min(reader->size(), first + static_cast<std::size_t>(count_arg.getValue()))
                        : reader->size();
  std::cerr << "odometry: " << toString(reader->kind()) << " (" << reader->sensorName() << "), scans "
            << first << ".." << end - 1 << " of " << reader->size() << ", config " << config_used << "\n";

  RadarOdometry odometry(params);
  ScanIterator scans(*reader, skip_arg.getValue(), first, end, kPrefetchScans);
  const auto t0 = Clock::now();
  std::size_t done = 0, lost = 0, keyframes = 0, widened = 0, second_motion = 0, prior_weighed = 0,
              prior_applied = 0;
  StageTimes total;
  std::vector<StepRecord> steps;
  ProgressLine progress("odometry", scans.total(), !quiet_arg.getValue());
  const auto tail = [&] { return "lost " + std::to_string(lost); };
  while (const auto scan = scans.next()) {
    const OdometryStep step = odometry.process(*scan);
    if (steps_arg.isSet()) steps.push_back(recordOf(step));
    ++done;
    lost += step.status == TrackingStatus::Lost;
    keyframes += step.new_keyframe;
    widened += step.widened;
    second_motion += step.second_motion;
    prior_weighed += step.prior_chi2 >= 0;
    prior_applied += step.prior_applied;
    const auto& t = step.times;
    total.cartesian += t.cartesian, total.detect += t.detect, total.describe += t.describe;
    total.align_prep += t.align_prep, total.match += t.match, total.clique += t.clique, total.svd += t.svd;
    total.refine += t.refine;
    progress.update(done + scans.skipped(), tail);
  }
  progress.finish(done + scans.skipped(), tail);
  const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
  const Trajectory& traj = odometry.trajectory();
  if (traj.empty()) throw InputError(dir.string(), "no scan could be read");
  writeTumTrajectory(out, traj);
  std::optional<StepTruth> truth;
  if (steps_arg.isSet() && reader->hasGroundTruth())
    truth = trueMotions(steps, [&reader](StampNs t) { return reader->groundTruthAt(t); });
  if (steps_arg.isSet()) writeTextAtomically(steps_arg.getValue(), formatSteps(steps, truth));

  const double n = static_cast<double>(done);
  std::printf("odometry summary\n");
  std::printf(
      "  scans          %zu tracked, %zu lost (constant-velocity prediction), %zu skipped, %zu keyframes; "
      "%zu "
      "re-matched with the wide radius (adaptive radius: the motion left its bound); %zu took the second "
      "rigid motion (the largest rigid set was moving)\n",
      done - lost, lost, scans.skipped(), keyframes, widened, second_motion);
  std::printf(
      "  motion prior   weighed in %zu scans, within its chi^2 gate (applied) in %zu; the other %zu: "
      "the motion left the model or the matches disagree with it\n",
      prior_weighed, prior_applied, prior_weighed - prior_applied);
  const ScanIteratorStats& input = scans.stats();
  std::printf(
      "  input          %zu duplicate scans skipped, %zu unreadable skipped, %zu blank scans, %zu time gaps "
      "(> 1.5x the %.3f s scan period, largest %.3f s)\n",
      input.skipped_duplicate, input.skipped_unreadable, input.blank, input.time_gaps,
      toSeconds(input.scan_period_ns), toSeconds(input.largest_gap_ns));
  std::printf("  path length    %.1f m in %.1f s of data\n", pathLength(traj),
              toSeconds(traj.back().stamp - traj.front().stamp));
  std::printf(
      "  speed          %.1f scans/s (%.1f ms/scan: cartesian %.1f, detect %.1f, describe %.1f, align %.1f, "
      "match %.1f, clique %.1f, svd %.2f, refine %.1f)\n",
      elapsed > 0 ? n / elapsed : 0.0, 1000 * elapsed / n, total.cartesian / n, total.detect / n,
      total.describe / n, total.align_prep / n, total.match / n, total.clique / n, total.svd / n,
      total.refine / n);
  std::printf("  trajectory     %s\n", out.string().c_str());
  if (steps_arg.isSet()) {
    std::printf("  steps          %s", steps_arg.getValue().c_str());
    const std::optional<StepTruthSummary> t =
        truth ? std::optional(summarizeTruth(steps, *truth)) : std::nullopt;
    if (t) {
      std::printf(" (true motion outside the search radius in %zu of %zu scans)", t->outside_radius,
                  t->compared);
    }
    std::printf("\n");
    if (t) {
      std::printf("  heading        straight scans (true turn < %.2f deg): ", kStraightDeg);
      if (t->straight > 0)
        std::printf("mean error %+.4f deg per scan over %zu scans",
                    t->straight_heading_error_deg / t->straight, t->straight);
      else
        std::printf("none");
      std::printf("; turning scans (>= %.1f deg): ", kTurningDeg);
      if (t->turning > 0)
        std::printf("%.1f %% of the true turn estimated over %zu scans",
                    100.0 * t->turning_estimated_deg / t->turning_true_deg, t->turning);
      else
        std::printf("none");
      std::printf("\n");
    }
  }

  if (reader->hasGroundTruth()) {
    std::optional<eval::EvalReport> evaluated;
    try {
      evaluated = eval::evaluate(traj, reader->groundTruth(), {}, out.string(), dir.string());
    } catch (const InputError& e) {
      // The trajectory is written; ground truth that does not cover it is the ground truth's problem.
      const std::string gt_file = groundTruthFile(*reader).string();
      if (eval_arg.isSet())  // the requested report cannot be made
        throw InputError(gt_file, "cannot evaluate " + out.string() + ": " + e.problem());
      logger().logFmt(mrpt::system::LVL_WARN, "%s: cannot evaluate %s: %s", gt_file.c_str(),
                      out.string().c_str(), e.problem().c_str());
      std::printf("  (not evaluated against %s: see the warning)\n", gt_file.c_str());
      return 0;
    }
    const eval::EvalReport& report = *evaluated;
    std::cout << eval::formatSummary(report);
    if (eval_arg.isSet()) {
      const fs::path eval_dir = eval_arg.getValue();
      eval::writeJsonReport(eval_dir / "report.json", report);
      const auto files = eval::writePlots(eval_dir, report);
      std::cout << "  report         " << (eval_dir / "report.json").string() << "\n  plots         ";
      for (const auto& f : files) std::cout << " " << f.string();
      std::cout << "\n";
    }
  } else {
    std::printf("  (no ground truth in this dataset: not evaluated)\n");
    if (eval_arg.isSet())
      logger().logFmt(mrpt::system::LVL_WARN, "--eval-dir ignored: the dataset has no ground truth");
  }
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("odometry", "Radar odometry (RadarSLAM pose tracking) over a dataset, TUM output + metrics",
                  runOdometry);

}  // namespace radarslam::cli
