// When stderr is not a terminal (a CI log, `2> log`), progress is whole lines, never a '\r', and
// the last line reports the whole run (issue 17: the demo's log held one 100 kB line).
#include <gtest/gtest.h>

#include <string>

#include "cli_run.h"
#include "temp_dir.h"

using radarslam::test::runCli;

namespace {
void expectWholeLineProgress(const std::string& err, const std::string& what, const std::string& cmd) {
  EXPECT_EQ(err.find('\r'), std::string::npos) << cmd << ": " << err;
  EXPECT_NE(err.find(what + ": 8/8 scans (100%), "), std::string::npos) << cmd << ": " << err;
  EXPECT_NE(err.find(" elapsed"), std::string::npos) << cmd << ": " << err;
}
}  // namespace

TEST(CliProgress, WholeLinesWhenStderrIsAFile) {
  radarslam::test::TempDir tmp;
  const std::string sim = "'" + (tmp / "sim").string() + "'";
  auto r = runCli("simulate " + sim + " --scans 8 --azimuths 128 --bins 512", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  expectWholeLineProgress(r.err, "simulate", "simulate");
  r = runCli("odometry " + sim + " -o '" + (tmp / "t.tum").string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  expectWholeLineProgress(r.err, "odometry", "odometry");
  r = runCli("map " + sim + " -o '" + (tmp / "m").string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  expectWholeLineProgress(r.err, "map", "map");
  r = runCli("localize '" + (tmp / "m").string() + "' " + sim + " -o '" + (tmp / "l.tum").string() + "'",
             tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  expectWholeLineProgress(r.err, "localize", "localize");
  EXPECT_NE(r.err.find(", localised "), std::string::npos) << r.err;  // its own figures after the rate
  EXPECT_NE(r.err.find(", fixes "), std::string::npos) << r.err;
  r = runCli("convert " + sim + " '" + (tmp / "s.rawlog").string() + "'", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  expectWholeLineProgress(r.err, "convert", "convert");
  r = runCli("odometry " + sim + " -o '" + (tmp / "q.tum").string() + "' --quiet", tmp);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("8/8 scans"), std::string::npos) << r.err;
}
