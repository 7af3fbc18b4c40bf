#pragma once
// A simulated dataset shared by the tests that need the same drive: `radarslam simulate DIR ARGS`
// runs once per program build and argument list, into RADARSLAM_TEST_CACHE_DIR (build/test-cache/),
// and every later caller gets the same directory. The tests only read it (a test that alters a
// dataset copies it first). Concurrent tests (ctest -j) wait on a lock file instead of simulating
// twice; the directory appears complete or not at all (simulated beside it, then renamed).
// Why: the simulator is deterministic per argument list, and under the sanitizers one 130-scan drive
// costs ~35 s; several suites simulated the same drives, once per test process.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "cli_run.h"

namespace radarslam::test {

/// The radarslam program that simulates the shared datasets: RADARSLAM_CLI, or
/// $RADARSLAM_TEST_SIMULATOR when set. The sanitizer stage (scripts/ci-hardening.sh) points it at
/// the Release build's program: the same deterministic drives without the instrumented simulator's
/// ~4x cost (the simulator itself is still tested under the sanitizers by test_sim and the
/// `simulate` CLI tests).
inline std::filesystem::path simulatorProgram() {
  if (const char* env = std::getenv("RADARSLAM_TEST_SIMULATOR"); env != nullptr && *env != '\0') return env;
  return RADARSLAM_CLI;
}

/// Identifies the current build of the simulating program (size and modification time): a rebuilt
/// program simulates again, and cache entries of older builds are removed.
inline std::string programStamp() {
  namespace fs = std::filesystem;
  const fs::path cli = simulatorProgram();
  const auto mtime = fs::last_write_time(cli).time_since_epoch();
  std::ostringstream s;
  s << "build-" << fs::file_size(cli) << "-"
    << std::chrono::duration_cast<std::chrono::nanoseconds>(mtime).count();
  return s.str();
}

/// Holds an exclusive flock on a file while in scope.
class FileLock {
 public:
  explicit FileLock(const std::filesystem::path& file)
      : fd_(::open(file.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + file.string());
  }
  ~FileLock() {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

/// The directory `radarslam simulate DIR ARGS` wrote (ARGS shell-quoted by the caller; no output
/// options). Throws std::runtime_error with the simulator's stderr if it fails.
inline std::filesystem::path simulatedDataset(const std::string& args) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(RADARSLAM_TEST_CACHE_DIR);
  const std::string stamp = programStamp();
  fs::create_directories(root);
  const FileLock lock(root / "lock");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root))  // entries of older builds: this cache's own
    if (entry.is_directory() && entry.path().filename().string().rfind("build-", 0) == 0 &&
        entry.path().filename() != stamp)
      fs::remove_all(entry.path(), ec);
  std::ostringstream key;
  key << "sim-" << std::hex << std::hash<std::string>{}(args);
  const fs::path dir = root / stamp / key.str();
  if (fs::exists(dir)) return dir;
  const fs::path partial = root / stamp / (key.str() + ".partial");
  fs::remove_all(partial, ec);  // left by a killed run of this cache
  fs::create_directories(partial.parent_path());
  const CliResult r = runCommand(simulatorProgram().string() + " simulate '" + partial.string() + "' " + args,
                                 partial.parent_path());
  if (r.code != 0)
    throw std::runtime_error("radarslam simulate " + args + ": exit " + std::to_string(r.code) + "\n" +
                             r.err);
  fs::rename(partial, dir);
  return dir;
}

}  // namespace radarslam::test
