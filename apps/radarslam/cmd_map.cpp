// `radarslam map DIR -o maps/NAME`: the full RadarSLAM system (paper Sec. III) over a dataset:
// tracking, local mapping with local BA, loop closing, pose-graph optimisation. Writes the
// keyframe map (maps/README.md) and, next to it, the trajectory, a grid preview, the loop list
// and a summary; with ground truth, the drift and loop-closure metrics.
#include <malloc.h>
#include <unistd.h>

#include <Eigen/LU>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/input_file.h>
#include <radarslam/core/log.h>
#include <radarslam/core/output_path.h>
#include <radarslam/core/version.h>
#include <radarslam/core/yaml_params.h>
#include <radarslam/eval/evaluate.h>
#include <radarslam/eval/plots.h>
#include <radarslam/eval/report.h>
#include <radarslam/io/dataset.h>
#include <radarslam/io/trajectory_files.h>
#include <radarslam/map/keyframe_culling.h>
#include <radarslam/map/map_exports.h>
#include <radarslam/map/map_io.h>
#include <radarslam/slam/loop_evaluation.h>
#include <radarslam/slam/map_consistency.h>
#include <radarslam/slam/radar_slam.h>

#include "cli_common.h"
#include "command.h"
#include "dataset_config.h"
#include "progress_line.h"
#include "slam_quality_json.h"

namespace radarslam::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Peak resident memory of this process (VmHWM), MiB; 0 if unknown.
double peakRssMiB() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0;
}

std::string loopsCsv(const std::vector<LoopRecord>& loops) {
  std::ostringstream s;
  s << "# query_keyframe,match_keyframe,descriptor_distance,accepted,rejected_by_graph,x,y,phi,inlier_ratio,"
       "ambiguity_ratio,sigma_x,sigma_y,sigma_phi,partial,confirmed,reason\n";
  for (const auto& l : loops) {
    // Marginal sigmas of the verifier's information (inf where it constrains nothing).
    Eigen::Vector3d sigma = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    if (const Eigen::FullPivLU<Eigen::Matrix3d> lu(l.information); lu.isInvertible())
      sigma = lu.inverse().diagonal().cwiseMax(0).cwiseSqrt();
    s << l.query << ',' << l.match << ',' << l.descriptor_distance << ',' << l.accepted << ','
      << l.rejected_by_graph << ',' << l.relative.x << ',' << l.relative.y << ',' << l.relative.phi << ','
      << l.inlier_ratio << ',' << l.ambiguity_ratio << ',' << sigma.x() << ',' << sigma.y() << ','
      << sigma.z() << ',' << l.slide << ',' << l.confirmed << ',' << l.reason << '\n';
  }
  return s.str();
}

int runMap(int argc, char** argv) {
  CommandLine cmd(
      "map",
      "Full RadarSLAM (paper Sec. III) over a radar dataset: pose tracking, local mapping with local "
      "bundle adjustment, loop closure (Algorithm 1 peak clouds, M2DP, ICP verification) and pose-graph "
      "optimisation. Writes the keyframe map to maps/NAME (format: maps/README.md) and in the same "
      "directory trajectory.tum (every scan), odometry.tum (front end only), grid.png (occupancy "
      "preview), loops.csv and summary.txt; with ground truth also eval/ (report.json and plots).");
  TCLAP::UnlabeledValueArg<std::string> dir_arg(
      "dataset", "Dataset directory (any supported layout) or .rawlog", true, "", "DIR", cmd.tclap());
  TCLAP::ValueArg<std::string> out_arg("o", "output",
                                       "Map name (maps/NAME) or directory; an existing map there is replaced",
                                       true, "", "MAP", cmd.tclap());
  TCLAP::ValueArg<std::string> config_arg("", "config",
                                          "Parameters (YAML; default: config/<sensor>.yaml for the detected "
                                          "dataset kind, or built-in defaults)",
                                          false, "", "FILE", cmd.tclap());
  TCLAP::ValueArg<int> threads_arg(
      "", "threads",
      "1: tracking, local mapping and loop closing in one thread (deterministic); "
      "3: each in its own thread, and the scans decoded ahead in a fourth (default: slam.threads of "
      "the config, 3)",
      false, 0, "N", cmd.tclap());
  TCLAP::SwitchArg skip_arg("", "skip-bad-scans", "Skip (with a warning) scans that cannot be read",
                            cmd.tclap());
  TCLAP::ValueArg<long long> first_arg("", "first", "First scan index (0-based)", false, 0, "N", cmd.tclap());
  TCLAP::ValueArg<long long> count_arg("", "count", "Number of scans (default: to the end)", false, -1, "N",
                                       cmd.tclap());
  TCLAP::ValueArg<double> grid_res_arg("", "grid-resolution",
                                       "Preview grid cell size, m (0.01..100, default 0.5)", false, 0.5, "M",
                                       cmd.tclap());
  TCLAP::ValueArg<std::string> extend_arg(
      "", "extend",
      "Extend this map (name in maps/ or a path) with the new session: it is relocalised in the map by its "
      "first verified loop and merged into one pose graph; the result (both sessions) is written to -o, "
      "which may be the same map",
      false, "", "MAP", cmd.tclap());
  TCLAP::SwitchArg force_arg("", "force",
                             "Let -o replace an empty directory or a regular file (a map is always "
                             "replaced; a non-empty directory that is not a map never is)",
                             cmd.tclap());
  TCLAP::SwitchArg quiet_arg("q", "quiet", "No progress line", cmd.tclap());
  cmd.parse(argc, argv);

  const std::string where = "radarslam map";
  if (first_arg.getValue() < 0) throw InputError(where, "--first must be >= 0");
  if (count_arg.isSet() && count_arg.getValue() < 1) throw InputError(where, "--count must be >= 1");
  if (threads_arg.isSet() && (threads_arg.getValue() < 1 || threads_arg.getValue() > 64))
    throw InputError(where, "--threads must be in 1..64");
  // A grid finer than 1 cm would not fit in memory for any real map (checked again on the map's
  // extent when the grid is made, before the map is swapped into place).
  if (!(grid_res_arg.getValue() >= 0.01 && grid_res_arg.getValue() <= 100))
    throw InputError(where, "--grid-resolution must be in [0.01, 100] m");
  const fs::path dir = dir_arg.getValue();
  if (!fs::exists(dir)) throw InputError(dir.string(), "no such file or directory");
  if (out_arg.getValue().empty()) throw InputError("-o", "empty output path");
  const fs::path map_dir = resolveMapPath(out_arg.getValue());
  checkNoOverlap(dir, map_dir);
  checkMapOutput(map_dir, force_arg.getValue());

  const auto reader = openDataset(dir);
  SlamParams params;
  std::string config_used = "built-in defaults", config_text;
  if (const auto config = findConfig(config_arg.getValue(), reader->kind())) {
    requireRegularFile(config->string());
    const YamlParams yaml = YamlParams::fromFile(config->string());
    loadParams(yaml, params);
    yaml.rejectUnknownKeys();
    config_used = config->string();
    std::ifstream in(*config);
    config_text.assign(std::istreambuf_iterator<char>(in), {});
  }
  if (threads_arg.isSet()) params.threads = threads_arg.getValue();

  const std::size_t first = static_cast<std::size_t>(first_arg.getValue());
  if (first >= reader->size())
    throw InputError(dir.string(), "--first " + std::to_string(first) + " is beyond the last scan (" +
                                       std::to_string(reader->size()) + " scans)");
  const std::size_t end =
      count_arg.isSet() ? std::min(reader->size(), first + static_cast<std::size_t>(count_arg.getValue()))
                        : reader->size();
  // Every input is checked before the first status line: a bad base map is one line of error.
  std::optional<KeyframeMap> base;
  fs::path base_dir;
  if (extend_arg.isSet()) {
    base_dir = resolveMapPath(extend_arg.getValue());
    base = loadMap(base_dir);
  }
  // Held in an optional: the SLAM state (~1.2 GB after 9 km) goes before the map is saved.
  std::optional<RadarSlam> slam_state(std::in_place, params);
  RadarSlam& slam = *slam_state;
  if (base) {
    try {
      slam.extend(*base);
    } catch (const std::invalid_argument& e) {
      throw InputError((base_dir / "manifest.yaml").string(), e.what());
    }
  }
  std::cerr << "map: " << toString(reader->kind()) << " (" << reader->sensorName() << "), scans " << first
            << ".." << end - 1 << " of " << reader->size() << ", config " << config_used << ", "
            << params.threads << (params.threads == 1 ? " thread" : " threads") << " -> " << map_dir.string()
            << "\n";

  if (base)
    std::cerr << "map: extending " << base_dir.string() << " (" << base->keyframes.size() << " keyframes)\n";
  // One thread means one: the scans are then decoded in the tracking thread too.
  ScanIterator scans(*reader, skip_arg.getValue(), first, end, params.threads >= 2 ? kPrefetchScans : 0);
  const auto t0 = Clock::now();
  std::size_t done = 0;
  ProgressLine progress("map", scans.total(), !quiet_arg.getValue());
  const auto tail = [&] {
    const SlamStats st = slam.stats();
    char buf[128];
    std::snprintf(buf, sizeof buf, "%zu keyframes, %zu loops, lost %zu", st.keyframes, st.loops_accepted,
                  st.lost_scans);
    return std::string(buf);
  };
  while (const auto scan = scans.next()) {
    slam.process(*scan);
    ++done;
    progress.update(done + scans.skipped(), tail);
  }
  progress.finish(done + scans.skipped(), tail);
  if (done == 0) throw InputError(dir.string(), "no scan could be read");
  const double track_s = std::chrono::duration<double>(Clock::now() - t0).count();
  try {
    slam.finish();
  } catch (const std::runtime_error& e) {
    throw InputError(extend_arg.getValue(), std::string("could not extend: ") + e.what());
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();

  KeyframeMap map = slam.map();
  map.meta.parameters_yaml = config_text;
  map.meta.source_dataset = fs::absolute(dir).lexically_normal().string();
  if (base) map.meta.source_dataset = base->meta.source_dataset + ";" + map.meta.source_dataset;
  map.meta.software_version = radarslam::versionText();
  const Trajectory traj = slam.trajectory();
  const Trajectory odometry = slam.odometryTrajectory();
  const auto loops = slam.loops();
  const SlamStats stats = slam.stats();
  slam_state.reset();  // everything the rest needs is copied out; `slam` must not be used below
  // The SLAM threads' allocator arenas keep the freed pages resident unless asked to give them back.
  malloc_trim(0);
  char buf[512];

  // The evaluation first: its report is one of the products saved with the map.
  std::optional<eval::EvalReport> report, odometry_report;
  std::string eval_text, quality_json;
  if (reader->hasGroundTruth()) {
    const Trajectory& gt = reader->groundTruth();
    const std::string gt_file = groundTruthFile(*reader).string();
    try {
      report = eval::evaluate(traj, gt, {}, "SLAM", dir.string());
      odometry_report = eval::evaluate(odometry, gt, {}, "odometry", dir.string());
      const eval::EvalReport& odo = *odometry_report;
      std::snprintf(
          buf, sizeof buf,
          "  accuracy       SLAM %.2f %% / %.4f deg/m, ATE %.2f m RMSE (odometry only: %.2f %% / %.4f "
          "deg/m, ATE %.2f m)\n",
          report->kitti.t_err_percent, report->kitti.r_err_deg_per_m, report->ate.trans_m.rmse,
          odo.kitti.t_err_percent, odo.kitti.r_err_deg_per_m, odo.ate.trans_m.rmse);
      eval_text += buf;
    } catch (const InputError& e) {  // ground truth that does not cover the run: the map is still made
      report.reset();
      logger().logFmt(mrpt::system::LVL_WARN, "%s: cannot evaluate the run: %s", gt_file.c_str(),
                      e.problem().c_str());
      eval_text += "  (ground truth " + gt_file + " does not cover the run: not evaluated)\n";
    }
    if (report) {
      LoopEvaluationParams lp;
      lp.exclude_recent = params.loop_closing.detector.exclude_recent;
      lp.exclude_recent_distance_m = params.loop_closing.detector.exclude_recent_distance_m;
      const LoopEvaluation le = evaluateLoops(map, loops, gt, lp);
      std::snprintf(
          buf, sizeof buf,
          "  loop truth     recall %.2f (%zu of %zu keyframes with a true loop), %zu false accepted "
          "(%zu left in the graph), max error of true loops %.2f m / %.2f deg, information NEES mean %.1f "
          "(%.0f %% within chi2(3) 95 %%); %zu partial loops (along one line), %zu of them false; "
          "%zu ambiguous places confirmed by the next keyframes, %zu of them false\n",
          le.recall, le.keyframes_with_loop_found, le.keyframes_with_true_loop, le.false_accepted,
          le.false_in_graph, le.max_error_m, le.max_error_deg, le.nees_mean, 100 * le.nees_within_95,
          le.slide_accepted, le.slide_false, le.confirmed_accepted, le.confirmed_false);
      eval_text += buf;
      std::size_t refused_right = 0;
      for (const auto& [reason, count] : le.refused_right) refused_right += count;
      eval_text += "  refused truth  " + std::to_string(refused_right) +
                   " refused candidates had the right pose (" + refusedRightText(le) + "), " +
                   std::to_string(le.refused_wrong) + " a wrong one\n";
      const MapConsistency mc = evaluateMapConsistency(map, gt);
      std::snprintf(
          buf, sizeof buf,
          "  map truth      revisit pairs within 10 m: %.1f %% consistent (%zu of %zu within 0.3 m / "
          "0.5 deg; median %.3f m, worst %.2f m / %.2f deg)\n",
          100 * mc.revisits.fraction, mc.revisits.consistent, mc.revisits.pairs, mc.revisits.median_error_m,
          mc.revisits.worst_error_m, mc.revisits.worst_error_deg);
      eval_text += buf;
      quality_json = slamQualityJson(*report, *odometry_report, le, mc);
      eval_text += "  evaluation     " + (map_dir / "eval" / "report.json").string() + " and plots in " +
                   (map_dir / "eval").string() + "\n";
    }
  } else {
    eval_text = "  (no ground truth in this dataset: not evaluated)\n";
  }

  // Map growth with area, not drive time: revisits' keyframes that an earlier pass covers are
  // dropped before saving (map/keyframe_culling.h); the evaluation above saw the whole run.
  const CullingReport culled = cullRedundantKeyframes(map, params.keyframe_culling);

  // Every run product goes into the temporary map directory: the swap into place is the last step,
  // so a failure anywhere (a too fine --grid-resolution, a full disk) leaves the previous map whole.
  std::ostringstream sum;
  MapSaveHooks hooks;
  const auto ts = Clock::now();
  hooks.write_products = [&](const fs::path& tmp) {
    const double save_ms = std::chrono::duration<double, std::milli>(Clock::now() - ts).count();
    writeTumTrajectory(tmp / "trajectory.tum", traj);
    writeTumTrajectory(tmp / "odometry.tum", odometry);
    writeTextAtomically(tmp / "loops.csv", loopsCsv(loops));
    GridExportParams grid;
    grid.resolution_m = grid_res_arg.getValue();
    if (!grid_res_arg
             .isSet()) {  // a city-scale map: the single-image grid coarser, full resolution in layers/
      const double fit = fittingGridResolution(map, grid);
      if (fit != grid.resolution_m)
        logger().logFmt(mrpt::system::LVL_INFO,
                        "grid.png/pgm/gridmap at %g m (at %g m the map is more than %zu cells; the full-"
                        "resolution grid is in layers/, tiled)",
                        fit, grid.resolution_m, grid.max_cells);
      grid.resolution_m = fit;
    }
    exportOccupancyGrid(map, tmp, "grid", grid);
    if (report) {
      fs::create_directories(tmp / "eval");
      eval::writeJsonReport(tmp / "eval" / "report.json", *report);
      if (!quality_json.empty()) writeTextAtomically(tmp / "eval" / "slam_quality.json", quality_json);
      eval::writePlots(tmp / "eval", *report);
    }

    sum << "map summary\n";
    std::snprintf(buf, sizeof buf,
                  "  scans          %zu processed (%zu lost: constant-velocity prediction), %zu skipped\n",
                  done, stats.lost_scans, scans.skipped());
    sum << buf;
    std::snprintf(
        buf, sizeof buf,
        "  map            %zu keyframes, %zu map points, %zu edges -> %s (saved in %.0f ms); %zu of %zu "
        "keyframes dropped where an earlier pass covers the place\n",
        map.keyframes.size(), map.points.size(), map.edges.size(), map_dir.string().c_str(), save_ms,
        culled.keyframes_before - culled.keyframes_after, culled.keyframes_before);
    sum << buf;
    std::snprintf(
        buf, sizeof buf,
        "  loops          %zu candidates verified: %zu accepted (%zu of them ambiguous places confirmed "
        "by the next keyframes; %zu confirmations held back by a rival placement, %zu withdrawn), "
        "%zu rejected by verification, %zu removed by the pose graph; %zu graph optimisations; "
        "%zu candidates by proximity where M2DP found none\n",
        stats.loop_candidates, stats.loops_accepted, stats.loops_confirmed, stats.confirmations_held_back,
        stats.confirmations_withdrawn, stats.loops_rejected, stats.loops_rejected_by_graph,
        stats.graph_optimisations, stats.proximity_candidates);
    sum << buf;
    const double n = static_cast<double>(done);
    std::snprintf(
        buf, sizeof buf,
        "  speed          %.1f scans/s overall (%.1f while tracking; finish %.1f s); per scan: tracking "
        "%.1f ms; per keyframe: local mapping %.1f ms, loop closing %.1f ms; %zu local BAs, graph "
        "%.0f ms total\n",
        n / elapsed, n / track_s, elapsed - track_s, stats.tracking_ms / n,
        stats.keyframes ? stats.local_mapping_ms / stats.keyframes : 0.0,
        stats.keyframes ? stats.loop_closing_ms / stats.keyframes : 0.0, stats.bundle_adjustments,
        stats.graph_ms);
    sum << buf;
    std::snprintf(buf, sizeof buf, "  memory         peak RSS %.0f MiB\n", peakRssMiB());
    sum << buf;
    sum << "  outputs        " << (map_dir / "trajectory.tum").string()
        << ", odometry.tum, grid.png, loops.csv, layers/ (grid, cloud, OctoMap for the map server)\n";
    sum << eval_text;
    writeTextAtomically(tmp / "summary.txt", sum.str());
  };
  saveMap(map, map_dir, hooks, params.map_layers);
  std::cout << sum.str();
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("map", "Full RadarSLAM over a dataset: keyframe map, trajectory, loops (maps/NAME)",
                  runMap);

}  // namespace radarslam::cli
