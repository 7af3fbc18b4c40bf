// `radarslam simulate --world grid|network|oxford-route`, `--scene`, `--route-from-gt` (docs/simulator.md):
// a bad value is one stderr line "radarslam: error: ..." naming the option or the file, exit code 1,
// and nothing left behind (neither OUT_DIR nor its hidden staging sibling); a network world writes
// exactly the scans asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "cli_run.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using radarslam::test::CliResult;
using radarslam::test::runCli;
using radarslam::test::shellQuoted;
using radarslam::test::TempDir;

/// Small scans: the option checks and the world generation are what is tested, not the rendering.
const std::string kSmall = " --azimuths 64 --bins 256";

/// The names in `dir` other than the captured stdout.txt/stderr.txt and the test's own inputs.
std::set<std::string> leftOver(const fs::path& dir, const std::set<std::string>& inputs) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n != "stdout.txt" && n != "stderr.txt" && !inputs.count(n)) out.insert(n);
  }
  return out;
}

struct BadSimulate {
  std::string name, args;            ///< args: OUT = the output directory, CSV = the input file
  std::string csv;                   ///< contents of CSV ("" : no such file is written)
  std::vector<std::string> needles;  ///< each must be in the error line
};

class SimulateWorldOptions : public ::testing::TestWithParam<BadSimulate> {};

TEST_P(SimulateWorldOptions, BadValueIsOneLineErrorAndLeavesNothing) {
  const BadSimulate& p = GetParam();
  TempDir tmp;
  const fs::path csv = tmp / "radar_odometry.csv";
  if (!p.csv.empty()) std::ofstream(csv, std::ios::binary) << p.csv;
  std::string args = p.args;
  for (std::size_t at; (at = args.find("OUT")) != std::string::npos;)
    args.replace(at, 3, shellQuoted(tmp / "out"));
  for (std::size_t at; (at = args.find("CSV")) != std::string::npos;) args.replace(at, 3, shellQuoted(csv));
  // --scans 3 unless the case is about --length-m: should a check be missing, the run stays short.
  if (args.find("--length-m") == std::string::npos) args += " --scans 3";
  const CliResult r = runCli("simulate " + args + kSmall, tmp);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("radarslam: error: ", 0), 0u) << r.err;
  for (const auto& n : p.needles)
    EXPECT_NE(r.err.find(n), std::string::npos) << "no '" << n << "' in: " << r.err;
  EXPECT_FALSE(fs::exists(tmp / "out"));
  EXPECT_EQ(leftOver(tmp.path(), {"radar_odometry.csv"}), std::set<std::string>{});
}

const char kOxfordHeader[] =
    "source_timestamp,destination_timestamp,x,y,z,roll,pitch,yaw,source_radar_timestamp,"
    "destination_radar_timestamp\n";

INSTANTIATE_TEST_SUITE_P(
    Simulate, SimulateWorldOptions,
    ::testing::Values(
        BadSimulate{"UnknownWorld", "OUT --world moon", "", {"--world", "'moon'"}},
        BadSimulate{"EmptyWorld", "OUT --world ''", "", {"--world"}},
        BadSimulate{"UnknownScene", "OUT --world network --scene jungle", "", {"--scene", "'jungle'"}},
        BadSimulate{"UnknownSceneOxfordRoute",
                    "OUT --route-from-gt CSV --scene jungle",
                    "x\n",
                    {"--scene", "'jungle'"}},
        BadSimulate{"OxfordRouteWithoutCsv", "OUT --world oxford-route", "", {"--route-from-gt", "required"}},
        BadSimulate{"CsvWithAnotherWorld",
                    "OUT --world network --route-from-gt CSV",
                    "x\n",
                    {"--route-from-gt", "oxford-route"}},
        BadSimulate{"MissingCsv", "OUT --route-from-gt CSV", "", {"--route-from-gt", "radar_odometry.csv"}},
        BadSimulate{"MissingCsvOxfordRoute",
                    "OUT --world oxford-route --route-from-gt CSV",
                    "",
                    {"--route-from-gt", "radar_odometry.csv"}},
        BadSimulate{"CsvIsADirectory", "OUT --route-from-gt OUT", "", {"--route-from-gt"}},
        BadSimulate{"CorruptCsvGarbage",
                    "OUT --route-from-gt CSV",
                    "this is not a CSV\n\x01\x02\xff\n",
                    {"radar_odometry.csv"}},
        BadSimulate{"CorruptCsvHeaderOnly", "OUT --route-from-gt CSV", kOxfordHeader, {"radar_odometry.csv"}},
        BadSimulate{"CorruptCsvBadRow",
                    "OUT --route-from-gt CSV",
                    std::string(kOxfordHeader) + "1547131046353776,1547131046103776,0.5,0.1,0,0,0,abc,"
                                                 "1547131046250020,1547131045999940\n",
                    {"radar_odometry.csv"}},
        BadSimulate{
            "CorruptCsvGap",
            "OUT --route-from-gt CSV",
            std::string(kOxfordHeader) +
                "1547131046353776,1547131046103776,0.5,0.1,0,0,0,0.01,1547131046250020,1547131045999940\n"
                "1547131046853776,1547131046603776,0.5,0.1,0,0,0,0.01,1547131046750020,1547131046500020\n",
            {"radar_odometry.csv", "gap"}},
        BadSimulate{"OxfordRouteWithLength",
                    "OUT --route-from-gt CSV --length-m 100",
                    "x\n",
                    {"--length-m", "oxford-route"}}),
    [](const auto& param_info) { return param_info.param.name; });

TEST(SimulateWorld, NetworkWritesExactlyTheScansAskedFor) {
  TempDir tmp;
  const fs::path out = tmp / "net";
  const CliResult r = runCli("simulate " + shellQuoted(out) + " --world network --scans 5" + kSmall, tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  std::size_t pngs = 0;
  for (const auto& e : fs::directory_iterator(out / "radar")) pngs += e.path().extension() == ".png";
  EXPECT_EQ(pngs, 5u);
  std::ifstream ts(out / "radar.timestamps");
  std::size_t stamps = 0;
  for (std::string line; std::getline(ts, line);) stamps += !line.empty();
  EXPECT_EQ(stamps, 5u);
  std::ifstream gt(out / "gt" / "radar_odometry.csv");
  std::size_t gt_rows = 0;
  for (std::string line; std::getline(gt, line);) gt_rows += !line.empty();
  EXPECT_EQ(gt_rows, 1u + 4u);  // the header, one row per consecutive pair
  EXPECT_NE(r.out.find("simulated 5 scans"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("world: network"), std::string::npos) << r.out;
  EXPECT_EQ(leftOver(tmp.path(), {"net"}), std::set<std::string>{});
}

// --compare-real takes any dataset the readers accept, not only Oxford's: the RADIATE fog scans
// against the simulated fog (docs/simulator.md, "Weather against real fog").
TEST(CliSimulate, CompareRealReadsTheRadiateFogScans) {
  RADARSLAM_REQUIRE_REAL_DATA(radiate, "radiate_tiny_foggy");
  TempDir tmp;
  const fs::path png = tmp / "cmp.png";
  const CliResult r =
      runCli("simulate " + shellQuoted(png) + " --weather fog --compare-real " + shellQuoted(radiate), tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("(18 scans)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("per range band"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("of 32 statistics within x1.5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("saturation streaks"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(">= 15 codes   real"), std::string::npos) << r.out;
  EXPECT_GT(fs::file_size(png), 10000u);
  EXPECT_EQ(leftOver(tmp.path(), {"cmp.png"}), std::set<std::string>{});
}

}  // namespace
