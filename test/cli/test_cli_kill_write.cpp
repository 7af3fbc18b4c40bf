// Atomic map writes under SIGKILL (issue #8 c): a map command overwriting an existing map is
// killed at many moments of its run; after every kill the map directory must load and hold either
// the previous map or the complete new one (never a mix or a partial file), and a later save must
// succeed and leave no temporary or backup directory behind.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/map/map_io.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The command under test, which (over)writes the map at {map} from the dataset at {data}: the
// SLAM mapping run itself (one thread: the same map every run).
const std::vector<std::string> kWriteCommand = {"map", "{data}",  "-o", "{map}", "--threads",
                                                "1",   "--count", "16", "-q"};
// The previous map: a shorter run, so the two maps differ.
const std::vector<std::string> kPreviousMapCommand = {"map", "{data}",  "-o", "{map}", "--threads",
                                                      "1",   "--count", "8",  "-q"};

std::vector<std::string> substitute(const std::vector<std::string>& args, const fs::path& data,
                                    const fs::path& map) {
  std::vector<std::string> out;
  for (std::string a : args) {
    if (a == "{data}") a = data.string();
    if (a == "{map}") a = map.string();
    out.push_back(a);
  }
  return out;
}

/// Starts `radarslam args...` with stdout/stderr to /dev/null; returns the child's pid.
pid_t start(const std::vector<std::string>& args) {
  std::vector<std::string> all = {RADARSLAM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

int waitExit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

int run(const std::vector<std::string>& args) { return waitExit(start(args)); }

/// Same map content; the creation time differs between runs of the same command.
bool sameContent(const radarslam::KeyframeMap& a, const radarslam::KeyframeMap& b) {
  return a.keyframes == b.keyframes && a.points == b.points && a.edges == b.edges &&
         a.meta.sensor == b.meta.sensor && a.meta.parameters_yaml == b.meta.parameters_yaml &&
         a.meta.source_dataset == b.meta.source_dataset;
}

class CliKillWrite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new radarslam::test::TempDir;
    data_ = *tmp_ / "sim";
    ASSERT_EQ(run({"simulate", data_.string(), "--scans", "40", "--seed", "3"}), 0);
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  static radarslam::test::TempDir* tmp_;
  static fs::path data_;
};
radarslam::test::TempDir* CliKillWrite::tmp_ = nullptr;
fs::path CliKillWrite::data_;

TEST_F(CliKillWrite, KilledOverwriteLeavesThePreviousOrTheNewMap) {
  const fs::path map = *tmp_ / "maps" / "killed";
  const fs::path ref = *tmp_ / "maps" / "reference";
  // The previous map A and, written elsewhere, the complete new map B (timing the full run).
  ASSERT_EQ(run(substitute(kPreviousMapCommand, data_, map)), 0);
  const auto t0 = Clock::now();
  ASSERT_EQ(run(substitute(kWriteCommand, data_, ref)), 0);
  const double full_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const radarslam::KeyframeMap a = radarslam::loadMap(map);
  const radarslam::KeyframeMap b = radarslam::loadMap(ref);
  ASSERT_FALSE(sameContent(a, b)) << "the test needs two different maps";

  // 8 kills at times spread over the whole run (reading, peak extraction, ...), then 8 inside the
  // save itself: as soon as the temporary map directory appears, plus 0-20 ms (files being
  // written and fsynced, the renames).
  struct Kill {
    double delay_s;
    bool after_save_starts;
  };
  std::vector<Kill> kills;
  for (int k = 0; k < 8; ++k) kills.push_back({full_s * k / 8.0, false});
  for (const double ms : {0, 1, 2, 3, 5, 8, 13, 20}) kills.push_back({ms / 1000.0, true});
  int kept_old = 0, got_new = 0, finished = 0, interrupted_saves = 0;
  for (const auto& kill : kills) {
    SCOPED_TRACE("kill " + std::to_string(kill.delay_s) + " s after " +
                 (kill.after_save_starts ? "the save started" : "the start") + " (full run " +
                 std::to_string(full_s) + " s)");
    const pid_t pid = start(substitute(kWriteCommand, data_, map));
    int code = 1000;  // not exited yet
    if (kill.after_save_starts) {
      const auto deadline = Clock::now() + std::chrono::duration<double>(10 * full_s + 10);
      while (!fs::exists(radarslam::mapTempDir(map)) && Clock::now() < deadline) {
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid) {
          code = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
          break;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    }
    if (code == 1000) {
      std::this_thread::sleep_for(std::chrono::duration<double>(kill.delay_s));
      ::kill(pid, SIGKILL);
      code = waitExit(pid);
    }
    finished += code == 0;
    ASSERT_TRUE(code == 0 || code == -SIGKILL) << "exit " << code;

    // What the kill left next to the map (for the printout: kills that hit the save itself).
    interrupted_saves += fs::exists(radarslam::mapTempDir(map)) || fs::exists(radarslam::mapBackupDir(map));
    radarslam::KeyframeMap loaded;
    ASSERT_NO_THROW(loaded = radarslam::loadMap(map));
    const bool is_old = sameContent(loaded, a), is_new = sameContent(loaded, b);
    ASSERT_TRUE(is_old || is_new) << "the map after the kill is neither the previous nor the new one";
    if (code == 0) {
      EXPECT_TRUE(is_new) << "a completed run must leave the new map";
    }
    kept_old += is_old;
    got_new += is_new;

    // A later save over whatever the kill left (a stale .killed.map-tmp, a backup) succeeds, loads,
    // and cleans up; it also puts A back for the next round.
    ASSERT_NO_THROW(radarslam::saveMap(a, map));
    EXPECT_FALSE(fs::exists(radarslam::mapTempDir(map)));
    EXPECT_FALSE(fs::exists(radarslam::mapBackupDir(map)));
    EXPECT_TRUE(sameContent(radarslam::loadMap(map), a));
  }
  std::printf(
      "full run %.2f s; after %zu kills: previous map %d, new map %d (%d runs finished first, "
      "%d kills left a temporary or backup directory)\n",
      full_s, kills.size(), kept_old, got_new, finished, interrupted_saves);
  // The schedule must really interrupt runs, and some kills must hit the save itself.
  EXPECT_GT(kept_old, 0);
  EXPECT_GT(interrupted_saves, 0);

  // An uninterrupted run over a map left by a kill completes with the new map.
  const pid_t pid = start(substitute(kWriteCommand, data_, map));
  std::this_thread::sleep_for(std::chrono::duration<double>(full_s * 0.95));
  ::kill(pid, SIGKILL);
  waitExit(pid);
  ASSERT_EQ(run(substitute(kWriteCommand, data_, map)), 0);
  EXPECT_TRUE(sameContent(radarslam::loadMap(map), b));
  EXPECT_FALSE(fs::exists(radarslam::mapTempDir(map)));
  EXPECT_FALSE(fs::exists(radarslam::mapBackupDir(map)));
}

}  // namespace
