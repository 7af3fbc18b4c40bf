// MRPT's own rawlog-edit (Debian mrpt-apps) reads our rawlogs through libradarslam_mrpt_plugin.so:
// the scan count, the stamps, each scan's getDescriptionAsText and a --cut, on a converted real
// Oxford sequence. Without the plugin rawlog-edit stops at the first scan (class not registered).
#include <gtest/gtest.h>
#include <mrpt/core/Clock.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "radarslam/core/time.h"
#include "radarslam/io/dataset.h"
#include "sanitized_build.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace radarslam;

namespace {

// rawlog-edit ARGS, its stdout and stderr together in `out`.
test::CliResult rawlogEdit(const std::string& args, const fs::path& dir) {
  test::CliResult r = test::runCommand("rawlog-edit " + args, dir);
  r.out += r.err;
  return r;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

class MrptPlugin : public ::testing::Test {
 protected:
  void SetUp() override {
#ifdef RADARSLAM_SANITIZED_BUILD
    // An ASan-instrumented plugin cannot be dlopen()ed by the uninstrumented rawlog-edit (the
    // sanitizer runtime must be loaded first); the Release stage runs this test.
    GTEST_SKIP() << "sanitizer build: rawlog-edit cannot load an instrumented plugin";
#endif
    if (std::system("command -v rawlog-edit > /dev/null 2>&1") != 0) {
      if (test::inCI()) FAIL() << "rawlog-edit (Debian mrpt-apps) is not installed: scripts/install-deps.sh";
      GTEST_SKIP() << "rawlog-edit not installed (apt-get install mrpt-apps)";
    }
    plugin_ = " --plugins '" + std::string(RADARSLAM_MRPT_PLUGIN) + "' ";
  }
  std::string plugin_;
  test::TempDir tmp_;
};

}  // namespace

TEST_F(MrptPlugin, RawlogEditListsDescribesAndCutsOurScans) {
  RADARSLAM_REQUIRE_REAL_DATA(oxford, "oxford_radar_robotcar_tiny");
  const fs::path rawlog = tmp_ / "ox.rawlog";
  ASSERT_EQ(test::runCli("convert '" + oxford.string() + "' '" + rawlog.string() + "'", tmp_).code, 0);
  const auto reader = openDataset(rawlog);
  ASSERT_EQ(reader->size(), 11u);

  const test::CliResult without = rawlogEdit("-i '" + rawlog.string() + "' --info", tmp_.path());
  EXPECT_NE(without.out.find("Overall number of objects         : 1\n"), std::string::npos) << without.out;

  const test::CliResult info = rawlogEdit(plugin_ + "-i '" + rawlog.string() + "' --info", tmp_.path());
  ASSERT_EQ(info.code, 0) << info.out;
  EXPECT_NE(info.out.find("Overall number of objects         : 11\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("All sensor labels                 : radar"), std::string::npos) << info.out;

  const fs::path stamps = tmp_ / "stamps.txt";
  ASSERT_EQ(rawlogEdit(plugin_ + "-i '" + rawlog.string() + "' --list-timestamps --text-file-output '" +
                           stamps.string() + "'",
                       tmp_.path())
                .code,
            0);
  std::ifstream in(stamps);
  std::vector<double> listed;
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    double t = 0;
    std::string label, cls;
    ls >> t >> label >> cls;
    EXPECT_EQ(label, "radar");
    EXPECT_EQ(cls, "radarslam::CObservationRadarScan");
    listed.push_back(t);
  }
  ASSERT_EQ(listed.size(), 11u);
  for (std::size_t i = 0; i < listed.size(); ++i)
    EXPECT_NEAR(listed[i], mrpt::Clock::toDouble(reader->readScan(i)->timestamp), 2e-6) << "scan " << i;

  const test::CliResult describe =
      rawlogEdit(plugin_ + "-i '" + rawlog.string() + "' --describe", tmp_.path());
  ASSERT_EQ(describe.code, 0) << describe.out;
  EXPECT_EQ(count(describe.out, "ClassName: radarslam::CObservationRadarScan"), 11u) << describe.out;
  EXPECT_EQ(count(describe.out, "Radar scan: 400 azimuths x 3768 bins, 0.0432 m/bin"), 11u) << describe.out;
  EXPECT_EQ(count(describe.out, "Sweep: first azimuth "), 11u) << describe.out;

  const fs::path cut = tmp_ / "cut.rawlog";
  ASSERT_EQ(rawlogEdit(plugin_ + "-i '" + rawlog.string() + "' --cut --from-index 2 --to-index 5 -o '" +
                           cut.string() + "'",
                       tmp_.path())
                .code,
            0);
  const auto cut_reader = openDataset(cut);
  ASSERT_EQ(cut_reader->size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(cut_reader->indexStamp(i), reader->indexStamp(i + 2));
}
