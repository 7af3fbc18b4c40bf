// `radarslam localize MAP DIR -o poses.tum`: relocalisation of a radar dataset in a stored map
// (module reloc): global fix by place recognition + verification, then tracking against the map.
// Writes the localised scans' poses (TUM) and a per-scan side file with status, covariance and fit
// (columns in docs/localization.md). With ground truth in DIR it reports the localisation errors.
// DDS (docs/dds.md): --publish sends every localised pose on rt/radarslam/pose; DIR = "dds:" takes
// the scans from rt/radarslam/radar_scan instead of a dataset (localize_dds.h); MAP = "dds:" takes the
// map from a radarslam-map-server's rt/radarslam/map_files (localize_map_dds.h).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <future>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/input_file.h>
#include <radarslam/core/log.h>
#include <radarslam/core/output_path.h>
#include <radarslam/core/yaml_params.h>
#include <radarslam/frontend/odometry.h>
#include <radarslam/io/dataset.h>
#include <radarslam/io/trajectory_files.h>
#include <radarslam/map/map_io.h>
#include <radarslam/reloc/localizer.h>
#include <radarslam/slam/slam_params.h>

#include <mrpt/poses/CPose2D.h>

#include "cli_common.h"
#include "command.h"
#include "dataset_config.h"
#include "eval_localization.h"
#include "localize_dds.h"
#include "localize_map_dds.h"
#include "localize_output.h"
#include "localize_truth.h"
#include "progress_line.h"

namespace radarslam::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

struct Fetched {
  CObservationRadarScan::Ptr scan;
  std::size_t index = 0, skipped = 0;
};

int runLocalize(int argc, char** argv) {
  CommandLine cmd(
      "localize",
      "Relocalisation in a stored map (issue #6): global localisation without an initial guess (M2DP "
      "place recognition over all map keyframes + geometric verification), then tracking of every scan "
      "against the map (odometry prediction + robust ICP against the local submap), with loss detection "
      "and automatic relocalisation. Writes the localised scans' poses (TUM) and FILE.csv with status, "
      "covariance and fit of every scan. See docs/localization.md.");
  TCLAP::UnlabeledValueArg<std::string> map_arg(
      "map",
      "Map name (maps/NAME) or directory; or dds: (dds:DOMAIN) to receive it from a radarslam-map-server "
      "(rt/radarslam/map_files: its files are checked into a private temporary directory, loaded, and "
      "removed; DOMAIN defaults to --domain)",
      true, "", "MAP", cmd.tclap());
  TCLAP::UnlabeledValueArg<std::string> dir_arg(
      "dataset",
      "Dataset directory (any supported layout) or .rawlog; or dds: (dds:TOPIC) for live scans over DDS "
      "(radarslam/RadarScan) until none arrived for --dds-timeout s",
      true, "", "DIR", cmd.tclap());
  TCLAP::ValueArg<std::string> out_arg("o", "output", "Output poses of the localised scans (TUM)", true, "",
                                       "FILE", cmd.tclap());
  TCLAP::ValueArg<std::string> config_arg(
      "", "config",
      "Parameters (YAML with the sections cartesian:, odometry:, localization:; default: "
      "config/<sensor>.yaml for the odometry and config/localization.yaml)",
      false, "", "FILE", cmd.tclap());
  TCLAP::SwitchArg skip_arg("", "skip-bad-scans", "Skip (with a warning) scans that cannot be read",
                            cmd.tclap());
  TCLAP::ValueArg<long long> first_arg("", "first", "First scan index (0-based)", false, 0, "N", cmd.tclap());
  TCLAP::ValueArg<long long> count_arg("", "count", "Number of scans (default: to the end)", false, -1, "N",
                                       cmd.tclap());
  TCLAP::ValueArg<std::string> eval_arg(
      "", "eval-dir", "With ground truth: write the per-scan errors (errors.csv) and summary.txt here", false,
      "", "DIR", cmd.tclap());
  TCLAP::SwitchArg quiet_arg("q", "quiet", "No progress line", cmd.tclap());
  TCLAP::SwitchArg publish_arg(
      "", "publish",
      "Publish every localised pose as geometry_msgs/PoseWithCovarianceStamped (frame map) on "
      "rt/radarslam/pose (ROS 2: /radarslam/pose)",
      cmd.tclap());
  TCLAP::ValueArg<unsigned> domain_arg("", "domain", "DDS domain id (ROS_DOMAIN_ID), 0..232", false, 0, "N",
                                       cmd.tclap());
  TCLAP::ValueArg<std::string> dds_config_arg(
      "", "dds-config", "Cyclone DDS XML configuration (default: built-in loopback, as config/dds.xml)",
      false, "", "FILE", cmd.tclap());
  TCLAP::ValueArg<double> dds_timeout_arg(
      "", "dds-timeout",
      "DIR = dds: ends after this many seconds without a scan; also the longest wait for "
      "--wait-subscribers and for pose acknowledgements at exit",
      false, 5.0, "S", cmd.tclap());
  TCLAP::ValueArg<double> map_timeout_arg(
      "", "map-timeout",
      "MAP = dds:, seconds to wait for a complete map (error and exit 1 when none arrived)", false, 30.0, "S",
      cmd.tclap());
  TCLAP::ValueArg<double> map_max_mb_arg(
      "", "map-max-mb",
      "MAP = dds:, refuse a map whose files add up to more than this many MiB (a hostile publisher on the "
      "domain must not fill the disk); valid (0, 1048576]",
      false, 4096, "MB", cmd.tclap());
  TCLAP::ValueArg<unsigned> wait_subs_arg("", "wait-subscribers",
                                          "With --publish: wait for N pose subscribers before the first scan",
                                          false, 0, "N", cmd.tclap());
  TCLAP::ValueArg<int> scan_queue_arg(
      "", "scan-queue",
      "With DIR = dds:, unread scans kept while the localiser is busy; older ones are dropped (4: stay "
      "live; larger: lose nothing of a fast replay)",
      false, 4, "N", cmd.tclap());
  TCLAP::ValueArg<std::string> sensor_arg("", "sensor",
                                          "With DIR = dds:, the odometry parameters of config/NAME.yaml "
                                          "(oxford, mulran, boreas, radiate; default: "
                                          "built-in odometry defaults); ignored with --config",
                                          false, "", "NAME", cmd.tclap());
  cmd.parse(argc, argv);

  const std::string where = "radarslam localize";
  if (first_arg.getValue() < 0) throw InputError(where, "--first must be >= 0");
  if (count_arg.isSet() && count_arg.getValue() < 1) throw InputError(where, "--count must be >= 1");
  const fs::path dir = dir_arg.getValue(), out = out_arg.getValue();
  LocalizeDdsOptions dds_opts;
  dds_opts.scan_topic = ddsScanTopic(dir_arg.getValue());
  dds_opts.publish = publish_arg.getValue();
  dds_opts.domain_id = domain_arg.getValue();
  dds_opts.config_file = dds_config_arg.getValue();
  dds_opts.timeout_s = dds_timeout_arg.getValue();
  dds_opts.wait_subscribers = wait_subs_arg.getValue();
  dds_opts.scan_queue = scan_queue_arg.getValue();
  const bool from_dds = dds_opts.scan_topic.has_value();
  if (from_dds && first_arg.getValue() != 0) throw InputError(where, "--first needs a dataset, not dds:");
  if (!from_dds && !fs::exists(dir)) throw InputError(dir.string(), "no such file or directory");
  const std::optional<std::uint32_t> map_domain = ddsMapDomain(map_arg.getValue(), domain_arg.getValue());
  if (map_domain && !(map_timeout_arg.getValue() > 0)) throw InputError(where, "--map-timeout must be > 0");
  if (!(map_max_mb_arg.getValue() > 0 && map_max_mb_arg.getValue() <= 1048576))
    throw InputError(where, "--map-max-mb must be in (0, 1048576]");
  fs::path map_dir = map_domain ? fs::path() : resolveMapPath(map_arg.getValue());
  if (!map_domain) checkNoOverlap(map_dir, out);
  if (!from_dds) checkNoOverlap(dir, out);
  checkFileOutput(out);
  // The per-scan side file FILE.csv goes next to a regular FILE (not next to /dev/null).
  const bool side_file = !isSpecialFile(followSymlinks(out));
  fs::path side_path = out;
  side_path += ".csv";
  fs::path boreas_path = out;
  boreas_path += ".boreas.txt";
  if (side_file) {
    if (!from_dds) checkNoOverlap(dir, side_path), checkNoOverlap(dir, boreas_path);
    checkFileOutput(side_path);
    checkFileOutput(boreas_path);
  }
  if (eval_arg.isSet()) {
    if (!map_domain) checkNoOverlap(map_dir, eval_arg.getValue());
    if (!from_dds) checkNoOverlap(dir, eval_arg.getValue());
    checkDirectoryOutput(eval_arg.getValue(), "--eval-dir");
  }

  // The DDS participant first: discovery overlaps with loading the map.
  std::unique_ptr<LocalizeDds> dds;
  if (from_dds || dds_opts.publish) dds = std::make_unique<LocalizeDds>(dds_opts);

  const auto t_load = Clock::now();
  std::string map_label = map_dir.string();  // what the log lines and the side file name
  std::unique_ptr<FetchedMap> fetched;
  if (map_domain) {
    fetched = std::make_unique<FetchedMap>(
        map_arg.getValue(),
        MapFetchOptions{*map_domain, dds_opts.config_file, map_timeout_arg.getValue(),
                        static_cast<std::uint64_t>(map_max_mb_arg.getValue() * 1048576.0)});
    map_dir = fetched->dir();
    const auto& r = fetched->received();
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s (map '%s' revision %u over DDS domain %u)", map_arg.getValue().c_str(),
                  r.map_name.c_str(), r.revision, *map_domain);
    map_label = buf;
    logger().logFmt(mrpt::system::LVL_INFO,
                    "localize: received map '%s' revision %u: %zu files, %zu chunks, %.1f MB in %.2f s",
                    r.map_name.c_str(), r.revision, r.files, r.chunks, static_cast<double>(r.bytes) / 1e6,
                    r.seconds);
  }
  const KeyframeMap map = loadMap(map_dir);
  fetched.reset();  // the received files are in memory now: remove the temporary directory
  if (map.keyframes.empty()) throw InputError(map_label, "the map has no keyframe");
  const double load_s = std::chrono::duration<double>(Clock::now() - t_load).count();

  const std::unique_ptr<DatasetReader> reader = from_dds ? nullptr : openDataset(dir);
  OdometryParams odo_params;
  LocalizerParams loc_params;
  std::string config_used;
  {
    std::vector<fs::path> files;
    if (config_arg.isSet()) {
      files.emplace_back(config_arg.getValue());
    } else {
      const std::string sensor_yaml =
          reader ? defaultConfigName(reader->kind())
                 : (sensor_arg.getValue().empty() ? std::string() : sensor_arg.getValue() + ".yaml");
      if (auto f = findConfigFile(sensor_yaml)) {
        files.push_back(*f);
      } else if (!reader && !sensor_yaml.empty()) {
        throw InputError(where, "--sensor " + sensor_arg.getValue() + ": no config/" + sensor_yaml);
      }
      if (auto f = findConfigFile("localization.yaml")) files.push_back(*f);
    }
    for (const auto& f : files) {
      requireRegularFile(f.string());
      const YamlParams yaml = YamlParams::fromFile(f.string());
      // Our own section first: the odometry loader accepts cartesian:/odometry: only, and
      // rejectUnknownKeys() below then checks the whole file.
      loadParams(yaml.section("localization"), loc_params);
      SlamParams all;  // the whole parameter set is validated (a sensor file also holds slam:)
      loadParams(yaml, all);
      odo_params = all.odometry;
      yaml.rejectUnknownKeys();
      if (!config_used.empty()) config_used.append(", ");
      config_used.append(f.string());
    }
    if (config_used.empty()) config_used = "built-in defaults";
  }

  const std::size_t first = static_cast<std::size_t>(first_arg.getValue());
  const std::size_t max_count =
      count_arg.isSet() ? static_cast<std::size_t>(count_arg.getValue()) : static_cast<std::size_t>(-1);
  std::size_t end = 0;  // dataset only
  std::cerr << "localize: map " << map_label << " (" << map.keyframes.size() << " keyframes, loaded in "
            << std::to_string(load_s).substr(0, 4) << " s), ";
  if (reader) {
    if (first >= reader->size())
      throw InputError(dir.string(), "--first " + std::to_string(first) + " is beyond the last scan (" +
                                         std::to_string(reader->size()) + " scans)");
    end = std::min(reader->size(), first + std::min(max_count, reader->size()));
    std::cerr << toString(reader->kind()) << " (" << reader->sensorName() << "), scans " << first << ".."
              << end - 1 << " of " << reader->size();
  } else {
    std::cerr << "DDS scans on " << *dds_opts.scan_topic << " (domain " << dds_opts.domain_id << ")";
  }
  std::cerr << ", config " << config_used << (dds_opts.publish ? ", publishing poses on DDS" : "") << "\n";

  const auto t_init = Clock::now();
  Localizer localizer(map, odo_params, loc_params);
  const double init_s = std::chrono::duration<double>(Clock::now() - t_init).count();

  if (dds && !dds->waitForPoseSubscribers())
    logger().logFmt(mrpt::system::LVL_WARN, "localize: fewer than %u pose subscribers after %.1f s, going on",
                    dds_opts.wait_subscribers, dds_opts.timeout_s);
  std::optional<ScanIterator> scans;
  if (reader) scans.emplace(*reader, skip_arg.getValue(), first, end);
  if (dds) dds->startScans();
  std::size_t received = 0;  // DDS scans
  auto fetch = [&scans, &dds, &received, max_count]() {
    Fetched f;
    if (scans) {
      f.scan = scans->next();
      f.index = scans->index();
      f.skipped = scans->skipped();
    } else if (received < max_count) {
      f.scan = dds->nextScan();  // nullptr: the stream ended (--dds-timeout)
      f.index = received++;
    }
    return f;
  };
  // Scan decoding (PNG) overlaps with localisation of the previous scan.
  std::future<Fetched> pending = std::async(std::launch::async, fetch);

  Trajectory poses;
  std::ostringstream side;
  side << "# radarslam localize: map " << map_label << ", dataset " << dir.string() << "\n"
       << "# stamp_s scan status localised x y phi cov_xx cov_xy cov_xphi cov_yy cov_yphi cov_phiphi "
          "fit_score "
          "inliers time_ms "
       << kSideFileExtraHeader << "\n";
  std::ostringstream boreas;
  char line[512];
  const auto truth = reader ? truthInMapFrame(map, *reader, dir) : std::nullopt;
  const bool gt = truth.has_value();
  std::vector<double> pos_err, head_err, map_pos_err, map_head_err, fits;
  Trajectory local_truth;  // the truth as the map places it (mapRelativeTruth), per localised scan
  std::ostringstream err_csv;
  err_csv << "# stamp_s scan status position_error_m heading_error_deg fit_score sigma_x_m sigma_y_m "
             "sigma_phi_deg map_position_error_m map_heading_error_deg\n";
  std::size_t done = 0, localised = 0, fixes = 0, far_off = 0, skipped = 0;
  std::size_t degraded_fixes = 0;   // fixes whose refinement was degenerate (localization.degraded_fixes)
  std::size_t contested_fixes = 0;  // fixes at places told apart by the map (resolve_contested_fixes)
  long first_fix = -1, first_trusted = -1;
  LocalizationTiming total;
  const auto t0 = Clock::now();
  const std::clock_t cpu0 = std::clock();
  auto last_scan_time = t0;
  // Dataset: done + skipped of the total, with ETA; a live DDS stream: no total, no ETA.
  ProgressLine bar("localize", scans ? scans->total() : 0, !quiet_arg.getValue(),
                   scans ? "scans" : "DDS scans", "scans");
  const ProgressLine::Tail tail = [&] {
    char buf[64];
    std::snprintf(buf, sizeof buf, "localised %.1f%%, fixes %zu", done > 0 ? 100.0 * localised / done : 0.0,
                  fixes);
    return std::string(buf);
  };
  for (;;) {
    Fetched f = pending.get();
    if (!f.scan) {
      skipped = f.skipped;
      break;
    }
    pending = std::async(std::launch::async, fetch);
    skipped = f.skipped;
    const LocalizationResult r = localizer.process(*f.scan);
    ++done;
    last_scan_time = Clock::now();
    total.odometry += r.timing.odometry, total.cloud += r.timing.cloud, total.tracking += r.timing.tracking;
    total.global += r.timing.global;
    const auto& c = r.covariance;
    std::snprintf(line, sizeof line,
                  "%s %zu %s %d %.4f %.4f %.6f %.6g %.6g %.6g %.6g %.6g %.6g %.4f %zu %.2f ",
                  formatStampSeconds(r.stamp).c_str(), f.index, toString(r.status), r.localised ? 1 : 0,
                  r.pose.x, r.pose.y, r.pose.phi, c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2),
                  r.fit_score, r.inliers, r.timing.total());
    side << line << sideFileExtra(map, r) << "\n";
    if (dds) dds->publishStatus(r, localizer.globalFixes(), r.localised);
    if (r.localised) {
      if (r.keyframe >= 0) boreas << boreasRow(map, r);
      ++localised;
      fixes += r.status == LocalizationStatus::GlobalFix;
      degraded_fixes += r.check == "degenerate_fix";
      contested_fixes +=
          r.contested_fix && (r.status == LocalizationStatus::GlobalFix || r.check == "degenerate_fix");
      if (first_fix < 0) first_fix = static_cast<long>(f.index - first);
      if (first_trusted < 0 &&
          (r.status == LocalizationStatus::Tracking || r.status == LocalizationStatus::GlobalFix))
        first_trusted = static_cast<long>(f.index - first);
      poses.push_back({r.stamp, r.pose});
      if (dds) dds->publishPose(r.stamp, r.pose, r.covariance);  // just after its status
      fits.push_back(r.fit_score);
      if (gt) {
        if (const auto t = interpolatePose(truth->truth, r.stamp)) {
          const double e = std::hypot(r.pose.x - t->x, r.pose.y - t->y);
          const double h = std::abs(std::remainder(r.pose.phi - t->phi, 2 * M_PI)) * 180 / M_PI;
          pos_err.push_back(e);
          head_err.push_back(h);
          far_off += e > 5.0;
          // Relative to the nearest map keyframe: without the map's own error.
          const auto rel = mapRelativeError(map, *truth, r.pose, *t);
          if (rel) map_pos_err.push_back(rel->first), map_head_err.push_back(rel->second);
          if (const auto local = mapRelativeTruth(map, *truth, r.pose, *t))
            local_truth.push_back({r.stamp, *local});
          std::snprintf(line, sizeof line, "%s %zu %s %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f\n",
                        formatStampSeconds(r.stamp).c_str(), f.index, toString(r.status), e, h, r.fit_score,
                        std::sqrt(c(0, 0)), std::sqrt(c(1, 1)), std::sqrt(c(2, 2)) * 180 / M_PI,
                        rel ? rel->first : NAN, rel ? rel->second : NAN);
          err_csv << line;
        }
      }
    }
    bar.update(done + skipped, tail);
  }
  // The final line; a DDS stream's once it ended, timed to its last scan (not the --dds-timeout).
  if (scans)
    bar.finish(done + skipped, tail);
  else if (done > 0)
    bar.finish(done, tail, last_scan_time);
  // A DDS stream ends with --dds-timeout s of silence: not part of the processing time.
  const double elapsed = std::chrono::duration<double>((scans ? Clock::now() : last_scan_time) - t0).count();
  const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  if (dds) dds->flush();
  if (done == 0)
    throw InputError(from_dds ? where : dir.string(),
                     from_dds ? "no scan received on " + *dds_opts.scan_topic + " within --dds-timeout"
                              : std::string("no scan could be read"));
  writeTumTrajectory(out, poses);
  if (side_file) writeTextAtomically(side_path, side.str()), writeTextAtomically(boreas_path, boreas.str());

  const double n = static_cast<double>(done);
  std::printf("localize summary\n");
  std::printf("  scans          %zu processed, %zu localised (%.1f %%), %zu skipped\n", done, localised,
              100.0 * localised / n, skipped);
  std::printf(
      "  global fixes   %zu + %zu degraded, %zu of them at contested places (relocalisations after the "
      "first: "
      "%zu), first fix at scan %ld, first trusted pose at scan %ld\n",
      fixes, degraded_fixes, contested_fixes, fixes + degraded_fixes > 0 ? fixes + degraded_fixes - 1 : 0,
      first_fix, first_trusted);
  std::printf("  median fit     %.3f (inlier ratio of the localised scans)\n", median(fits));
  std::printf("  model error    %.3f m, %.3f deg added to each registration's covariance (%s)\n",
              localizer.registrationModel().position_sigma_floor_m,
              localizer.registrationModel().heading_sigma_floor_deg,
              map.meta.clouds_motion_compensated ? "a SLAM map: tracker.icp.slam_map_*_sigma_floor_*"
                                                 : "a map of raw sweeps: tracker.icp.*_sigma_floor_*");
  std::printf(
      "  speed          %.1f scans/s (%.1f ms/scan: odometry %.1f, cloud %.1f, tracking %.1f, global %.1f); "
      "map "
      "load %.2f s, init %.2f s\n"
      "                 CPU %.1f ms/scan (both threads; scan decoding overlaps) = %.1f scans per CPU "
      "second\n",
      n / elapsed, 1000 * elapsed / n, total.odometry / n, total.cloud / n, total.tracking / n,
      total.global / n, load_s, init_s, 1000 * cpu_s / n, n / cpu_s);
  std::printf("  poses          %s (%zu localised scans), per-scan details %s\n", out.string().c_str(),
              localised, side_file ? side_path.string().c_str() : "not written (-o is a special file)");
  if (dds_opts.publish)
    std::printf("  published      %zu poses on %s and %zu statuses on %s (domain %u)\n",
                dds->posesPublished(), ddsPoseTopic(), done, ddsStatusTopic(), dds_opts.domain_id);
  if (gt) {
    std::ostringstream s;
    s << "  truth          " << truth->how << "\n";
    char buf[384];
    std::snprintf(
        buf, sizeof buf,
        "  vs ground truth  %zu localised scans with ground truth: position error median %.3f m, max "
        "%.3f m; heading error median %.3f deg, max %.3f deg; %zu scans > 5 m off\n",
        pos_err.size(), median(pos_err),
        pos_err.empty() ? NAN : *std::max_element(pos_err.begin(), pos_err.end()), median(head_err),
        head_err.empty() ? NAN : *std::max_element(head_err.begin(), head_err.end()), far_off);
    s << buf;
    std::snprintf(buf, sizeof buf,
                  "  vs the map     relative to the nearest map keyframe: position error median %.3f m, max "
                  "%.3f m; heading error median %.3f deg, max %.3f deg\n",
                  median(map_pos_err),
                  map_pos_err.empty() ? NAN : *std::max_element(map_pos_err.begin(), map_pos_err.end()),
                  median(map_head_err),
                  map_head_err.empty() ? NAN : *std::max_element(map_head_err.begin(), map_head_err.end()));
    s << buf;
    if (side_file && !local_truth.empty()) {  // consistency against the truth as the map places it
      const LocalizationScore score = scoreLocalization(side_path, local_truth);
      std::snprintf(
          buf, sizeof buf,
          "  consistency    vs the map: NEES mean %.2f (3 if calibrated), %.1f %% within the chi2(3) 95 "
          "%% bound; position part %.2f (2), heading part %.2f (1); %zu localised scans\n",
          score.nees_mean, 100 * score.nees_within_95, score.nees_xy_mean, score.nees_yaw_mean,
          score.with_truth);
      s << buf;
    }
    std::cout << s.str();
    if (eval_arg.isSet()) {
      const fs::path eval_dir = eval_arg.getValue();
      fs::create_directories(eval_dir);
      writeTextAtomically(eval_dir / "errors.csv", err_csv.str());
      std::snprintf(buf, sizeof buf,
                    "scans %zu\nlocalised %zu\nlocalised_percent %.2f\nglobal_fixes %zu\ndegraded_fixes %zu\n"
                    "contested_fixes %zu\nfirst_fix_scan %ld\nfirst_trusted_scan %ld\nmedian_fit "
                    "%.4f\nscans_per_s %.2f\n",
                    done, localised, 100.0 * localised / n, fixes, degraded_fixes, contested_fixes, first_fix,
                    first_trusted, median(fits), n / elapsed);
      writeTextAtomically(eval_dir / "summary.txt", std::string(buf).append(s.str()));
      // The truth in the map frame: GT of `radarslam eval --localization FILE.csv E/truth_map.tum`.
      writeTumTrajectory(eval_dir / "truth_map.tum", truth->truth);
      // ... and as the map places it (nearest keyframe), per localised scan: the consistency above.
      if (!local_truth.empty()) writeTumTrajectory(eval_dir / "truth_local.tum", local_truth);
      std::cout << "  eval           " << (eval_dir / "errors.csv").string() << ", "
                << (eval_dir / "summary.txt").string() << ", " << (eval_dir / "truth_map.tum").string()
                << "\n";
    }
  } else {
    std::printf(
        "  (not evaluated: no ground truth in the map's frame - needs absolute gt/poses.tum in the map's "
        "source dataset and in DIR, or a map built from DIR)\n");
    if (eval_arg.isSet())
      logger().logFmt(mrpt::system::LVL_WARN, "--eval-dir ignored: the dataset has no ground truth");
  }
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("localize", "Relocalisation in a stored map: global fix + map tracking, TUM output",
                  runLocalize);

}  // namespace radarslam::cli
