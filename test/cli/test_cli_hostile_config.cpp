// Hostile configs and numeric options, end to end: each must end in exactly one stderr line
// "radarslam: error: <file>: ..." naming the file and the key, exit code 1, and no output file.
// Deep nesting (MRPT's parser used to overflow the stack), binary and invalid-UTF-8 files, YAML
// syntax errors (libfyaml's own diagnostics must not leak), a scalar top level, every class of
// out-of-range parameter, absurd coordinates in trajectories, and export sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"
#include "file_contents.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace {

using radarslam::test::writeFileBytes;

namespace fs = std::filesystem;
using radarslam::test::CliResult;
using radarslam::test::runCli;
using radarslam::test::shellQuoted;
using radarslam::test::TempDir;

std::size_t lineCount(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

/// Exit 1, one line "radarslam: error: ...", naming every one of `needles`.
void expectOneLineError(const CliResult& r, const std::vector<std::string>& needles) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("radarslam: error: ", 0), 0u) << r.err;
  for (const auto& n : needles)
    EXPECT_NE(r.err.find(n), std::string::npos) << "no '" << n << "' in: " << r.err;
}

/// `radarslam odometry <oxford tiny> -o OUT --config CFG` with CFG = `text`.
CliResult runOdometryConfig(const fs::path& data, const TempDir& tmp, const std::string& text,
                            const std::string& name = "cfg.yaml") {
  const fs::path cfg = tmp / name;
  writeFileBytes(cfg, text);
  return runCli("odometry " + shellQuoted(data) + " -q --count 2 -o " + shellQuoted(tmp / "out.tum") +
                    " --config " + shellQuoted(cfg),
                tmp);
}

std::string deepFlow(std::size_t n) { return "x: " + std::string(n, '[') + std::string(n, ']') + "\n"; }
std::string deepMaps(std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += "{a: ";
  return s + "1" + std::string(n, '}') + "\n";
}
/// Block-style nesting: "- - - ... 1" (indentation nesting grows quadratically in size).
std::string deepDashes(std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += "- ";
  return s + "1\n";
}
std::string deepBlock(std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += std::string(i, ' ') + "a:\n";
  return s + std::string(n, ' ') + "b: 1\n";
}

struct DeepText {
  std::string name, text;
};

class HostileConfigNesting : public ::testing::TestWithParam<DeepText> {};

TEST_P(HostileConfigNesting, DeepNestingIsOneLineErrorNotACrash) {
  RADARSLAM_REQUIRE_REAL_DATA(data, "oxford_radar_robotcar_tiny");
  TempDir tmp;
  const CliResult r = runOdometryConfig(data, tmp, GetParam().text, "deep.yaml");
  expectOneLineError(r, {"deep.yaml", "nested more than 64"});
  EXPECT_FALSE(fs::exists(tmp / "out.tum"));
}

INSTANTIATE_TEST_SUITE_P(HostileConfig, HostileConfigNesting,
                         ::testing::Values(DeepText{"Flow", deepFlow(20000)},
                                           DeepText{"Maps", deepMaps(20000)},
                                           DeepText{"Dashes", deepDashes(20000)},
                                           DeepText{"Block", deepBlock(3000)}),
                         [](const auto& param_info) { return param_info.param.name; });

TEST(HostileConfigManifest, DeepManifestIsOneLineError) {
  TempDir tmp;
  const fs::path map = tmp / "map";
  fs::create_directories(map);
  writeFileBytes(map / "manifest.yaml", deepFlow(20000));
  const CliResult r = runCli("export " + shellQuoted(map) + " --cloud -o " + shellQuoted(tmp / "out"), tmp);
  expectOneLineError(r, {"manifest.yaml", "nested more than 64"});
  EXPECT_FALSE(fs::exists(tmp / "out" / "cloud.ply"));
}

struct BadText {
  std::string name, text, needle;
};

class HostileConfigText : public ::testing::TestWithParam<BadText> {};

TEST_P(HostileConfigText, IsOneLineErrorNamingTheFile) {
  RADARSLAM_REQUIRE_REAL_DATA(data, "oxford_radar_robotcar_tiny");
  TempDir tmp;
  const CliResult r = runOdometryConfig(data, tmp, GetParam().text);
  expectOneLineError(r, {"cfg.yaml", GetParam().needle});
  EXPECT_EQ(r.err.find("MRPT"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("must be a map"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "out.tum"));
}

constexpr char kPngBytes[] = "\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x10\0\0\0\x10\x08\x06\0\0\0";
const std::string kPng(kPngBytes, sizeof kPngBytes - 1);

INSTANTIATE_TEST_SUITE_P(
    HostileConfig, HostileConfigText,
    ::testing::Values(BadText{"Png", kPng, "binary"},
                      BadText{"NulBytes", std::string("odometry:\n\0\0\0\0", 14), "NUL byte"},
                      BadText{"ControlBytes", "odometry:\n  \x01\x02\x03: 1\n", "control byte"},
                      BadText{"InvalidUtf8", "odometry:\n  keypoints: \xff\xfe\xc3\n", "UTF-8"},
                      BadText{"UnclosedFlow", "odometry: [1, 2\nslam: 3\n", "line 3, column 1"},
                      BadText{"UnclosedMap", "odometry: {keypoints: 1\n", "line 2, column 1"},
                      BadText{"BadIndent", "a: 1\n  b: 2\n c: 3\n", "line 1, column 4"},
                      BadText{"UnclosedQuote", "odometry: \"abc\n", "without closing quote"},
                      BadText{"Scalar", "hello\n", "map of parameters"},
                      BadText{"Null", "~\n", "map of parameters"},
                      BadText{"List", "- 1\n- 2\n", "map of parameters"}),
    [](const auto& param_info) { return param_info.param.name; });

TEST(HostileConfigText, EmptyOrCommentOnlyConfigKeepsTheDefaults) {
  RADARSLAM_REQUIRE_REAL_DATA(data, "oxford_radar_robotcar_tiny");
  TempDir tmp;
  for (const std::string& text : {std::string(), std::string("# nothing\n\n")}) {
    SCOPED_TRACE("config '" + text + "'");
    const CliResult r = runOdometryConfig(data, tmp, text);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(tmp / "out.tum"));
    fs::remove(tmp / "out.tum");
  }
}

struct BadValue {
  std::string name, yaml, key;
};

class HostileConfigRange : public ::testing::TestWithParam<BadValue> {};

TEST_P(HostileConfigRange, OdometryConfigIsOneLineErrorNamingFileAndKey) {
  RADARSLAM_REQUIRE_REAL_DATA(data, "oxford_radar_robotcar_tiny");
  TempDir tmp;
  const CliResult r = runOdometryConfig(data, tmp, GetParam().yaml);
  expectOneLineError(r, {"cfg.yaml", "'" + GetParam().key + "'"});
  EXPECT_FALSE(fs::exists(tmp / "out.tum"));
}

INSTANTIATE_TEST_SUITE_P(
    HostileConfig, HostileConfigRange,
    ::testing::Values(
        BadValue{"MaxKeypoints", "odometry:\n  keypoints:\n    max_keypoints: 1000000000\n",
                 "odometry.keypoints.max_keypoints"},
        BadValue{"CompensationPasses", "odometry:\n  tracking:\n    compensation_passes: 1000000000\n",
                 "odometry.tracking.compensation_passes"},
        BadValue{"BlurSigma", "odometry:\n  keypoints:\n    blur_sigma_px: 1e6\n",
                 "odometry.keypoints.blur_sigma_px"},
        BadValue{"MaxMatches", "odometry:\n  outliers:\n    max_matches: -1\n",
                 "odometry.outliers.max_matches"},
        BadValue{"PatchSize", "odometry:\n  keypoints:\n    patch_size: 0\n",
                 "odometry.keypoints.patch_size"},
        BadValue{"PyramidLevels", "odometry:\n  keypoints:\n    pyramid_levels: 1000\n",
                 "odometry.keypoints.pyramid_levels"},
        BadValue{"MetresPerPixel", "cartesian:\n  m_per_px: 1e-9\n", "cartesian.m_per_px"},
        BadValue{"ImageSize", "cartesian:\n  size_px: 100000\n", "cartesian.size_px"},
        BadValue{"MinRange", "odometry:\n  tracking:\n    min_range_m: 1e9\n",
                 "odometry.tracking.min_range_m"},
        BadValue{"NegativePatchRadius", "odometry:\n  patch_alignment:\n    patch_radius_px: -3\n",
                 "odometry.patch_alignment.patch_radius_px"},
        BadValue{"NanRatio", "odometry:\n  matching:\n    ratio: nan\n", "odometry.matching.ratio"},
        BadValue{"InfRadius", "odometry:\n  matching:\n    radius_m: inf\n", "odometry.matching.radius_m"},
        BadValue{"CliqueSteps", "odometry:\n  outliers:\n    max_clique_steps: 1e15\n",
                 "odometry.outliers.max_clique_steps"},
        BadValue{"Detector", "odometry:\n  keypoints:\n    detector: sift\n", "odometry.keypoints.detector"},
        BadValue{"Threads", "slam:\n  threads: 100000\n", "slam.threads"},
        BadValue{"IntervalAboveWindow", "slam:\n  local_mapping:\n    interval_keyframes: 50\n",
                 "slam.local_mapping.interval_keyframes"},
        BadValue{"RotationSteps", "slam:\n  loop_closure:\n    verifier:\n      rotation_steps: 100000000\n",
                 "slam.loop_closure.verifier.rotation_steps"},
        BadValue{"VoteGrid", "slam:\n  loop_closure:\n    verifier:\n      vote_cell_m: 0.01\n",
                 "slam.loop_closure.verifier.vote_cell_m"},
        BadValue{"M2dpRings", "slam:\n  loop_closure:\n    m2dp:\n      rings: 1000000\n",
                 "slam.loop_closure.m2dp.rings"},
        BadValue{"PeakRange", "slam:\n  loop_closure:\n    peak_cloud:\n      min_range_m: 1e9\n",
                 "slam.loop_closure.peak_cloud.min_range_m"},
        BadValue{"PeakRangeOrder",
                 "slam:\n  loop_closure:\n    peak_cloud:\n      min_range_m: 50\n      max_range_m: 10\n",
                 "slam.loop_closure.peak_cloud.max_range_m"},
        BadValue{"Candidates", "slam:\n  loop_closure:\n    detector:\n      max_candidates: 1000000000\n",
                 "slam.loop_closure.detector.max_candidates"},
        BadValue{"PoseGraph", "slam:\n  pose_graph:\n    max_iterations: 1000000000\n",
                 "slam.pose_graph.max_iterations"}),
    [](const auto& param_info) { return param_info.param.name; });

class HostileConfigSimRange : public ::testing::TestWithParam<BadValue> {};

TEST_P(HostileConfigSimRange, SimulatorConfigIsOneLineErrorNamingFileAndKey) {
  TempDir tmp;
  const fs::path cfg = tmp / "sim.yaml";
  writeFileBytes(cfg, GetParam().yaml);
  const CliResult r = runCli("simulate " + shellQuoted(tmp / "out") + " --config " + shellQuoted(cfg), tmp);
  expectOneLineError(r, {"sim.yaml", "'" + GetParam().key + "'"});
  EXPECT_FALSE(fs::exists(tmp / "out"));
}

INSTANTIATE_TEST_SUITE_P(
    HostileConfig, HostileConfigSimRange,
    ::testing::Values(BadValue{"NegativeScans", "scans: -5\n", "scans"},
                      BadValue{"Rays", "physics:\n  rays_per_azimuth: 100000\n", "physics.rays_per_azimuth"},
                      BadValue{"BlocksX", "world:\n  blocks_x: 100000\n", "world.blocks_x"},
                      BadValue{"Bins", "radar:\n  bins: 10000000\n", "radar.bins"},
                      BadValue{"BlockOrder", "world:\n  block_min_m: 200\n  block_max_m: 100\n",
                               "world.block_max_m"},
                      BadValue{"Speed", "route:\n  city_speed_mps: 0\n", "route.city_speed_mps"}),
    [](const auto& param_info) { return param_info.param.name; });

struct BadOption {
  std::string name, args, needle;
};

class HostileConfigOption : public ::testing::TestWithParam<BadOption> {};

TEST_P(HostileConfigOption, IsOneLineErrorBeforeAnyWork) {
  TempDir tmp;
  std::string args = GetParam().args;
  for (std::size_t at; (at = args.find("OUT")) != std::string::npos;)
    args.replace(at, 3, shellQuoted(tmp / "out"));
  const CliResult r = runCli(args, tmp);
  expectOneLineError(r, {GetParam().needle});
  EXPECT_FALSE(fs::exists(tmp / "out"));
}

INSTANTIATE_TEST_SUITE_P(
    HostileConfig, HostileConfigOption,
    ::testing::Values(BadOption{"SimScans", "simulate OUT --scans 1000000000", "--scans"},
                      BadOption{"SimLength", "simulate OUT --length-m 1e9", "--length-m"},
                      BadOption{"SimTraversal", "simulate OUT --traversal 7", "--traversal"},
                      BadOption{"SimResolution", "simulate OUT --resolution 1e-9", "--resolution"},
                      BadOption{"SimImage", "simulate OUT --azimuths 16384 --bins 65535", "--azimuths"},
                      BadOption{"MapThreads", "map nowhere -o OUT --threads 100000", "--threads"},
                      BadOption{"MapGrid", "map nowhere -o OUT --grid-resolution 1e-6", "--grid-resolution"},
                      BadOption{"MapSynthEvery", "map-synth nowhere -o OUT --every 1e12", "--every"},
                      BadOption{"CartResolution", "cart nowhere OUT.png --resolution 1e-9", "--resolution"},
                      BadOption{"EvalLengths", "eval nowhere nowhere --lengths 1e308", "--lengths"},
                      BadOption{"EvalStep", "eval nowhere nowhere --step 4000000000", "--step"}),
    [](const auto& param_info) { return param_info.param.name; });

struct AbsurdX {
  std::string name, x;
};

class HostileConfigTrajectory : public ::testing::TestWithParam<AbsurdX> {};

TEST_P(HostileConfigTrajectory, AbsurdTrajectoryCoordinateIsOneLineErrorAsEstimateAndAsTruth) {
  TempDir tmp;
  writeFileBytes(tmp / "gt.tum", "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n3.0 2 0 0 0 0 0 1\n");
  writeFileBytes(tmp / "est.tum",
                 "1.0 0 0 0 0 0 0 1\n2.0 " + GetParam().x + " 0 0 0 0 0 1\n3.0 2 0 0 0 0 0 1\n");
  for (const auto& [first, second] : {std::pair{"est.tum", "gt.tum"}, std::pair{"gt.tum", "est.tum"}}) {
    SCOPED_TRACE(std::string("eval ") + first + " " + second);
    const CliResult r = runCli("eval " + shellQuoted(tmp / first) + " " + shellQuoted(tmp / second) +
                                   " --plot-dir " + shellQuoted(tmp / "plots"),
                               tmp);
    expectOneLineError(r, {"est.tum"});
    EXPECT_FALSE(fs::exists(tmp / "plots"));
  }
}

INSTANTIATE_TEST_SUITE_P(HostileConfig, HostileConfigTrajectory,
                         ::testing::Values(AbsurdX{"Huge", "1e308"}, AbsurdX{"FarNegative", "-2e7"},
                                           AbsurdX{"Inf", "inf"}),
                         [](const auto& param_info) { return param_info.param.name; });

TEST(HostileConfigPhysical, OctomapOfTooManyVoxelsIsRefusedWithItsSize) {
  RADARSLAM_REQUIRE_REAL_DATA(data, "oxford_radar_robotcar_tiny");
  TempDir tmp;
  const fs::path map = tmp / "map";
  CliResult r = runCli("map-synth " + shellQuoted(data) + " -o " + shellQuoted(map), tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  r = runCli("export " + shellQuoted(map) + " --octomap --resolution 0.005 --verbosity WARN -o " +
                 shellQuoted(tmp / "out"),
             tmp);
  expectOneLineError(
      r, {"cells is too large", "--resolution"});  // the grid_columns fill is bounded by its raster
  EXPECT_FALSE(fs::exists(tmp / "out" / "map.bt"));
}

TEST(HostileConfigShipped, ShippedSimulatorConfigIsInRange) {
  // config/<sensor>.yaml are covered by SlamParams.EveryShippedConfigLoadsWithNoUnknownKey.
  TempDir tmp;
  const fs::path src = RADARSLAM_SOURCE_DIR;
  const CliResult r = runCli("simulate " + shellQuoted(tmp / "sim") + " --scans 1 --config " +
                                 shellQuoted(src / "config" / "sim.yaml"),
                             tmp);
  EXPECT_EQ(r.code, 0) << r.err;
}

}  // namespace
