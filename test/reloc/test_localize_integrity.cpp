// Integrity monitoring (issue #14), end to end on simulated drives: a kidnapped vehicle (the scans
// of ~130 m of the route cut out: the vehicle jumps ahead between two scans) and a drive that leaves the
// mapped area and comes back. No scan may be reported `tracking`/`global_fix` more than 2 m or 2 deg off, and
// a new trusted fix must come within a bounded number of scans after the vehicle is back in the map. With
// `integrity: {enabled: false}` (the tracker's own tests only) these fail (docs/localization.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "file_contents.h"
#include "radarslam/map/map_io.h"
#include "simulated_dataset.h"
#include "temp_dir.h"

namespace radarslam {
namespace {

using radarslam::test::readFileBytes;

namespace fs = std::filesystem;

/// `radarslam ARGS` (cli_run.h) succeeds; else its exit code, stdout and stderr.
::testing::AssertionResult runs(const std::string& args, const fs::path& dir) {
  const test::CliResult r = test::runCli(args, dir);
  if (r.code == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "radarslam " << args << ": exit " << r.code << "\n"
                                       << r.out << r.err;
}

std::vector<std::vector<std::string>> rows(const fs::path& p) {
  std::vector<std::vector<std::string>> out;
  std::ifstream f(p);
  for (std::string line; std::getline(f, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> cols;
    for (std::string c; ss >> c;) cols.push_back(c);
    out.push_back(cols);
  }
  return out;
}

/// Scan file stamps (us) of a simulated dataset, in order.
std::vector<long long> scanStamps(const fs::path& dir) {
  std::vector<long long> out;
  std::ifstream f(dir / "radar.timestamps");
  for (long long t = 0, valid = 0; f >> t >> valid;) out.push_back(t);
  return out;
}

/// A copy of `src` without the scans [skip_from, skip_to) (the ground truth, by time, kept whole).
/// (Scan images carry their azimuth times, so scans cannot be moved in time: a kidnapping is a jump.)
void dropScans(const fs::path& src, const fs::path& dst, std::size_t skip_from, std::size_t skip_to) {
  const auto stamps = scanStamps(src);
  fs::create_directories(dst / "radar");
  fs::copy(src / "gt", dst / "gt", fs::copy_options::recursive);
  std::ofstream ts(dst / "radar.timestamps");
  for (std::size_t k = 0; k < stamps.size(); ++k) {
    if (k >= skip_from && k < skip_to) continue;
    const std::string name = std::to_string(stamps[k]) + ".png";
    fs::copy_file(src / "radar" / name, dst / "radar" / name);
    ts << stamps[k] << " 1\n";
  }
}

constexpr std::size_t kScans = 130;

class LocalizeIntegrity : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new test::TempDir;
    const std::string n = "--scans " + std::to_string(kScans);
    t1_ = new fs::path(test::simulatedDataset(n));
    t2_ = new fs::path(test::simulatedDataset(n + " --traversal 2"));
  }
  static void TearDownTestSuite() {
    delete tmp_;
    delete t1_;
    delete t2_;
  }

  /// Localises `dataset` in `map`; the rows of errors.csv (stamp scan status pos_err head_err ...) and
  /// the side file.
  static void localize(const fs::path& map, const fs::path& dataset, const std::string& name,
                       std::size_t scans, std::vector<std::vector<std::string>>& errors,
                       std::vector<std::vector<std::string>>& side, const std::string& config = "") {
    const fs::path d = tmp_->path();
    const fs::path poses = d / (name + ".tum");
    ASSERT_TRUE(runs("localize '" + map.string() + "' '" + dataset.string() + "' -o '" + poses.string() +
                         "' --eval-dir '" + (d / (name + "_eval")).string() + "' -q" +
                         (config.empty() ? "" : " --config '" + config + "'"),
                     d));
    errors = rows(d / (name + "_eval") / "errors.csv");
    side = rows(poses.string() + ".csv");
    ASSERT_EQ(side.size(), scans);
  }

  static void driveOutOfTheMapAndBack(const std::string& name, bool adaptive_odometry);

  static test::TempDir* tmp_;
  static fs::path *t1_, *t2_;  ///< the two traversals (test::simulatedDataset, shared; read only)
};
test::TempDir* LocalizeIntegrity::tmp_ = nullptr;
fs::path* LocalizeIntegrity::t1_ = nullptr;
fs::path* LocalizeIntegrity::t2_ = nullptr;

bool trusted(const std::string& status) { return status == "tracking" || status == "global_fix"; }

/// Every trusted scan within 2 m / 2 deg; returns the scan indices of trusted scans within 1 m.
std::vector<std::size_t> checkTrusted(const std::vector<std::vector<std::string>>& errors) {
  std::vector<std::size_t> good;
  for (const auto& r : errors) {
    if (!trusted(r[2])) continue;
    const double e = std::stod(r[3]), h = std::stod(r[4]);
    EXPECT_LE(e, 2.0) << "scan " << r[1] << " " << r[2] << " is " << e << " m off";
    EXPECT_LE(h, 2.0) << "scan " << r[1] << " " << r[2] << " is " << h << " deg off";
    if (e <= 1.0 && h <= 1.0) good.push_back(std::stoul(r[1]));
  }
  return good;
}

/// config/oxford.yaml and config/localization.yaml in one file at `path`, with the localisation
/// key `zeroed` (when not empty) set to 0.
void writeShippedConfig(const fs::path& path, const std::string& zeroed) {
  std::string loc = readFileBytes(fs::path(RADARSLAM_SOURCE_DIR) / "config" / "localization.yaml");
  if (!zeroed.empty()) {
    const auto at = loc.find(zeroed + ": ");
    ASSERT_NE(at, std::string::npos) << zeroed;
    loc.replace(at, loc.find('\n', at) - at, zeroed + ": 0");
  }
  std::ofstream(path) << readFileBytes(fs::path(RADARSLAM_SOURCE_DIR) / "config" / "oxford.yaml") << loc;
}

TEST_F(LocalizeIntegrity, KidnappedVehicleIsNeverTrustedWhileWrong) {
  const fs::path d = tmp_->path();
  ASSERT_TRUE(runs("map-synth '" + t1_->string() + "' -o '" + (d / "map").string() + "'", d));
  // Scans 0-44, then from 95 on: the vehicle is carried ~130 m further along the route.
  dropScans(*t2_, d / "kidnap", 45, 95);
  std::vector<std::vector<std::string>> errors, side;
  // config/oxford.yaml's odometry and a self-trusting tracker; RADARSLAM_TEST_NO_INTEGRITY=1 turns
  // the checks off (to see this test fail without them).
  const fs::path config = d / "self_trusting.yaml";
  {
    std::ofstream c(config);
    c << readFileBytes(fs::path(RADARSLAM_SOURCE_DIR) / "config" / "oxford.yaml")
      << "localization:\n  map_sweep_period_s: 0.25\n  integrity:\n    enabled: "
      << (std::getenv("RADARSLAM_TEST_NO_INTEGRITY") ? "false" : "true")
      << "\n  tracker:\n    min_fit_score: 0.1\n    min_inliers: 20\n    max_rms_m: 1.0\n"
         "    max_jump_m: 10.0\n    max_jump_deg: 20.0\n    max_position_sigma_m: 5.0\n";
  }
  localize(d / "map", d / "kidnap", "kidnap", kScans - 50, errors, side, config.string());
  const auto good = checkTrusted(errors);
  // A correct trusted pose within 10 scans of the kidnapping (scan 45 of the cut dataset; issue 14:
  // recovery within 10 scans). Measured: lost at 45-46, global fix at 47.
  bool found = false;
  for (const std::size_t s : good) found = found || (s >= 45 && s < 55);
  EXPECT_TRUE(found) << "no correct trusted pose within 10 scans after the kidnapping";
}

/// The map lacks traversal 1's scans 40-99 (~150 m of road); traversal 2 drives through the hole.
/// Inside it a look-alike street verifies as a global fix 108 m off (scan 61) with the adaptive
/// odometry radius, and in the clang sanitizer build with the fixed one: the dead-reckoned pose's
/// chi^2 gate (localization.gate_fixes_with_odometry) must reject it. RADARSLAM_TEST_NO_GATE=1
/// turns the gate off (to see this test fail without it).
void LocalizeIntegrity::driveOutOfTheMapAndBack(const std::string& name, bool adaptive_odometry) {
  const fs::path d = tmp_->path();
  if (!fs::exists(d / "map_gap")) {
    dropScans(*t1_, d / "t1_gap", 40, 100);
    ASSERT_TRUE(runs("map-synth '" + (d / "t1_gap").string() + "' -o '" + (d / "map_gap").string() + "'", d));
  }
  const fs::path config = d / (name + ".yaml");
  {
    std::string loc = readFileBytes(fs::path(RADARSLAM_SOURCE_DIR) / "config" / "localization.yaml");
    auto set = [&loc](const std::string& key, bool value) {
      const auto at = loc.find(key + ": ");
      ASSERT_NE(at, std::string::npos) << key;
      const auto end = loc.find_first_of(" \n", at + key.size() + 2);
      loc.replace(at, end - at, key + ": " + (value ? "true" : "false"));
    };
    set("odometry_adaptive_radius", adaptive_odometry);
    set("gate_fixes_with_odometry", std::getenv("RADARSLAM_TEST_NO_GATE") == nullptr);
    std::ofstream c(config);
    c << readFileBytes(fs::path(RADARSLAM_SOURCE_DIR) / "config" / "oxford.yaml") << loc;
  }
  std::vector<std::vector<std::string>> errors, side;
  localize(d / "map_gap", *t2_, name, kScans, errors, side, config.string());
  const auto good = checkTrusted(errors);
  // Back in the map from about scan 100: a correct trusted pose within 20 scans.
  bool found = false;
  for (const std::size_t s : good) found = found || (s >= 100 && s < 120);
  EXPECT_TRUE(found) << "no correct trusted pose after returning into the map";
}

TEST_F(LocalizeIntegrity, DriveOutOfTheMapAndBack) { driveOutOfTheMapAndBack("gap", false); }

TEST_F(LocalizeIntegrity, DriveOutOfTheMapAndBackWithAdaptiveOdometryRadius) {
  driveOutOfTheMapAndBack("gap_adaptive", true);
}

/// The map holds the street of traversal 1's keyframes 15-44 (of 59) twice: the second copy (new keyframes,
/// their own odometry edges, no edge to the first: a revisit the SLAM run did not merge) moved
/// rigidly by 1.5 m / 1.0 m / 1.5 deg, with stamps outside the truth (the map frame is fitted to the
/// first copy only). Traversal 2 enters the street from the part of the map that exists once: it
/// must stay on that copy (every trusted pose within 1 m / 1 deg of the truth) and report the
/// ambiguity. RADARSLAM_TEST_NO_COPIES=1 (submap.max_path_m 0: every keyframe near) shows what
/// happens without telling the copies apart.
TEST_F(LocalizeIntegrity, MapWithTheSameStreetTwiceIsTrackedOnOneCopyAndReported) {
  const fs::path d = tmp_->path();
  ASSERT_TRUE(runs("map-synth '" + t1_->string() + "' -o '" + (d / "map").string() + "'", d));
  KeyframeMap map = loadMap(d / "map");
  const std::size_t first = 15, last = 45, n = map.keyframes.size();
  ASSERT_GT(n, last);
  // The drift of an unmerged revisit: 1.8 m and 1.5 deg.
  const double kShiftX = 1.5, kShiftY = 1.0, dphi = 1.5 * M_PI / 180, c = std::cos(dphi), s = std::sin(dphi);
  const mrpt::math::TPose2D centre = map.keyframes[30].pose;  // a copy: push_back below reallocates
  std::uint64_t next_id = map.keyframes.back().id + 1;
  const StampNs later = map.keyframes.back().stamp_ns + 3600'000'000'000LL;
  for (std::size_t k = first; k < last; ++k) {
    Keyframe copy = map.keyframes[k];
    const double x = copy.pose.x - centre.x, y = copy.pose.y - centre.y;
    copy.pose = {centre.x + c * x - s * y + kShiftX, centre.y + s * x + c * y + kShiftY,
                 copy.pose.phi + dphi};
    copy.id = next_id++;
    copy.stamp_ns = later + static_cast<StampNs>(k) * 250'000'000LL;
    if (k > first) {
      PoseGraphEdge e;
      e.from = copy.id - 1;
      e.to = copy.id;
      const auto& a = map.keyframes[k - 1].pose;
      const auto& b = map.keyframes[k].pose;
      const double ca = std::cos(a.phi), sa = std::sin(a.phi);
      e.relative = {ca * (b.x - a.x) + sa * (b.y - a.y), -sa * (b.x - a.x) + ca * (b.y - a.y),
                    std::remainder(b.phi - a.phi, 2 * M_PI)};
      e.information = {1e2, 0, 0, 0, 1e2, 0, 0, 0, 1e4};
      map.edges.push_back(e);
    }
    map.keyframes.push_back(std::move(copy));
  }
  saveMap(map, d / "map_twice");

  const fs::path config = d / "twice.yaml";
  writeShippedConfig(config, std::getenv("RADARSLAM_TEST_NO_COPIES") ? "max_path_m" : "");
  std::vector<std::vector<std::string>> errors, side;
  localize(d / "map_twice", *t2_, "twice", kScans, errors, side, config.string());
  std::size_t trusted_scans = 0;
  for (const auto& r : errors) {
    if (!trusted(r[2])) continue;
    ++trusted_scans;
    EXPECT_LE(std::stod(r[3]), 1.0) << "scan " << r[1] << " " << r[2] << " (the other copy?)";
    EXPECT_LE(std::stod(r[4]), 1.0) << "scan " << r[1] << " " << r[2];
  }
  EXPECT_GE(trusted_scans, kScans * 8 / 10);
  std::size_t ambiguous = 0;
  for (const auto& r : side) ambiguous += r.back() == "ambiguous";
  EXPECT_GE(ambiguous, 10u) << "the second copy was never reported";
}

/// A map that disagrees with itself (issue 14; docs/localization.md check (i)): 40 m of the map's
/// keyframes turned by 3 deg about their middle, as a loop correction concentrated between keyframes
/// would leave them. Where the registration follows the rest of the submap, the pose relative to the
/// nearest keyframe (what a client uses, and what errors.csv's map columns score) is ~3 deg off:
/// such a scan must not be trusted. With RADARSLAM_TEST_NO_MAP_CHECK=1 (tracker.anchor_path_m: 0)
/// it is.
TEST_F(LocalizeIntegrity, AMapThatDisagreesWithItselfIsNotTrustedWhereItDisagrees) {
  const fs::path d = tmp_->path();
  ASSERT_TRUE(runs("map-synth '" + t1_->string() + "' -o '" + (d / "map").string() + "'", d));
  KeyframeMap map = loadMap(d / "map");
  const std::size_t n = map.keyframes.size();
  ASSERT_GT(n, 40u);
  const mrpt::math::TPose2D pivot = map.keyframes[n / 2].pose;
  const double twist = 3 * M_PI / 180, c = std::cos(twist), s = std::sin(twist);
  std::size_t twisted = 0;
  for (Keyframe& k : map.keyframes) {
    const double x = k.pose.x - pivot.x, y = k.pose.y - pivot.y;
    if (std::hypot(x, y) > 20) continue;
    k.pose = {pivot.x + c * x - s * y, pivot.y + s * x + c * y, k.pose.phi + twist};
    ++twisted;
  }
  ASSERT_GE(twisted, 5u);
  saveMap(map, d / "map_twisted");
  const fs::path config = d / "twisted.yaml";
  writeShippedConfig(config, std::getenv("RADARSLAM_TEST_NO_MAP_CHECK") ? "anchor_path_m" : "");
  std::vector<std::vector<std::string>> errors, side;
  localize(d / "map_twisted", *t2_, "twisted", kScans, errors, side, config.string());
  std::size_t trusted_scans = 0, flagged = 0;
  for (const auto& r : errors) {
    if (!trusted(r[2])) continue;
    ++trusted_scans;
    const double e = std::stod(r[9]), h = std::stod(r[10]);  // relative to the nearest map keyframe
    EXPECT_LE(e, 2.0) << "scan " << r[1] << " " << r[2] << " is " << e << " m off the nearest keyframe";
    EXPECT_LE(h, 2.0) << "scan " << r[1] << " " << r[2] << " is " << h << " deg off the nearest keyframe";
  }
  for (const auto& r : side) flagged += r.back() == "map";
  EXPECT_GE(trusted_scans, kScans * 6 / 10);
  if (!std::getenv("RADARSLAM_TEST_NO_MAP_CHECK")) {
    EXPECT_GE(flagged, 1u) << "check (i) never fired";
  }
}

/// Where every registration is flat along its weakest direction (here forced: a 1 cm
/// tracker.icp.profile_shift_m, which no scan can tell from its solution), a verified global fix refines only
/// to a `degenerate` registration. localization.degraded_fixes reports it `degraded` (check `degenerate_fix`)
/// with the refinement's inflated covariance and tracks on from it; without it
/// (RADARSLAM_TEST_NO_DEGRADED_FIXES=1) every scan stays `lost`. Nothing may be trusted, and the
/// degraded poses must lie within their own 3 sigma.
TEST_F(LocalizeIntegrity, AFixInAFlatPlaceIsReportedDegradedAndTrackedOn) {
  const fs::path d = tmp_->path();
  if (!fs::exists(d / "map")) {
    ASSERT_TRUE(runs("map-synth '" + t1_->string() + "' -o '" + (d / "map").string() + "'", d));
  }
  const fs::path config = d / "flat.yaml";
  {
    std::string loc = readFileBytes(fs::path(RADARSLAM_SOURCE_DIR) / "config" / "localization.yaml");
    auto set = [&loc](const std::string& key, const std::string& value) {
      const auto at = loc.find(key + ": ");
      ASSERT_NE(at, std::string::npos) << key;
      loc.replace(at, loc.find_first_of(" \n", at + key.size() + 2) - at, key + ": " + value);
    };
    set("profile_shift_m", "0.01");
    set("degraded_fixes", std::getenv("RADARSLAM_TEST_NO_DEGRADED_FIXES") ? "false" : "true");
    std::ofstream(config) << readFileBytes(fs::path(RADARSLAM_SOURCE_DIR) / "config" / "oxford.yaml") << loc;
  }
  std::vector<std::vector<std::string>> errors, side;
  localize(d / "map", *t2_, "flat", kScans, errors, side, config.string());
  EXPECT_TRUE(checkTrusted(errors).empty()) << "a flat registration was trusted";
  // side: stamp scan status localised x y phi cov_xx cov_xy cov_xphi cov_yy ... check
  long first = -1;
  std::size_t localised = 0, within = 0;
  for (std::size_t k = 0; k < side.size(); ++k) {
    if (side[k][3] != "1") continue;
    if (first < 0) {
      first = static_cast<long>(k);
      EXPECT_EQ(side[k][2], "degraded");
      EXPECT_EQ(side[k].back(), "degenerate_fix");
    }
    ++localised;
  }
  for (const auto& r : errors) {
    if (r[2] != "degraded") continue;
    // The position error against 3 sigma of the covariance's largest axis (side file of the same scan).
    const auto& s = side.at(std::stoul(r[1]));
    const double xx = std::stod(s[7]), xy = std::stod(s[8]), yy = std::stod(s[10]);
    const double largest = 0.5 * (xx + yy) + std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
    within += std::stod(r[3]) <= 3 * std::sqrt(largest);
  }
  ASSERT_GE(first, 0) << "no scan localised: a degenerate fix was refused";
  EXPECT_LE(first, 2) << "first fix later than the third scan";
  EXPECT_GE(localised, kScans * 9 / 10);
  EXPECT_GE(within, localised * 95 / 100) << "degraded poses outside their own 3 sigma";
}

}  // namespace
}  // namespace radarslam
