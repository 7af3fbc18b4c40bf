#pragma once
// Helpers for the DDS tests: child processes with captured output, per-test DDS domain ids,
// synthetic maps built with addKeyframe.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <stdexcept>

#include <radarslam/map/keyframe_map.h>
#include <radarslam/map/map_from_trajectory.h>
#include "file_contents.h"

extern char** environ;

namespace radarslam::test {

/// A DDS domain id for this test: `index` (0..24) is distinct per test (test/dds: 0..20, the Fast DDS
/// interop tests 21..24), the pid spreads runs of the
/// suite. Two tests running at the same time never share an id: equal ids need equal indices
/// (the pid part is a multiple of 25), i.e. the same test. Ids stay within 1..200 (Cyclone: < 233).
inline unsigned testDomainId(unsigned index) {
  if (index >= 25) throw std::logic_error("testDomainId: index must be < 25");
  return 1 + (static_cast<unsigned>(::getpid()) % 8) * 25 + index;
}

/// Factor applied to every process timeout in these tests: RADARSLAM_TEST_TIME_SCALE (default 1).
/// The sanitizer stage of CI sets it (ASan makes the localiser ~5x slower); the timeouts only
/// bound a hang, they never decide a measurement.
inline double timeScale() {
  const char* s = std::getenv("RADARSLAM_TEST_TIME_SCALE");
  const double v = s ? std::atof(s) : 1.0;
  return v >= 1.0 ? v : 1.0;
}

inline std::string readText(const std::filesystem::path& p) { return radarslam::test::readFileBytes(p); }

/// A child process with stdout/stderr captured to files; killed (SIGKILL) if still running at
/// destruction.
class Child {
 public:
  Child(const std::vector<std::string>& args, const std::filesystem::path& log_stem) {
    out_ = log_stem.string() + ".out";
    err_ = log_stem.string() + ".err";
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int rc = posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) throw std::runtime_error("cannot start " + args[0]);
  }
  ~Child() {
    if (running()) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  pid_t pid() const { return pid_; }
  bool running() {
    if (exited_) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) finish(status);
    return !exited_;
  }
  /// Waits for the exit; returns the exit code (128 + signal if killed), or -1 on timeout.
  int wait(double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s * timeScale());
    while (running()) {
      if (std::chrono::steady_clock::now() > deadline) return -1;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return code_;
  }
  void signal(int sig) { ::kill(pid_, sig); }
  std::string out() const { return readText(out_); }
  std::string err() const { return readText(err_); }
  /// Waits until stderr contains `text` n times (e.g. a status line); false on timeout or exit.
  bool waitForLog(const std::string& text, double timeout_s, int n = 1) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s * timeScale());
    for (;;) {
      const std::string e = err();
      int found = 0;
      for (std::size_t pos = e.find(text); pos != std::string::npos; pos = e.find(text, pos + 1)) ++found;
      if (found >= n) return true;
      if (!running() || std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }

 private:
  void finish(int status) {
    exited_ = true;
    code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  pid_t pid_ = -1;
  bool exited_ = false;
  int code_ = -1;
  std::string out_, err_;
};

/// A map of `keyframes` keyframes on a line, each seeing `points` random returns spread over the
/// square [-half, half]^2 (world frame) plus the four corners, so the grid spans the square plus
/// the export margin.
inline KeyframeMap syntheticMap(int keyframes, int points, double half, unsigned seed) {
  KeyframeMap map;
  map.meta.sensor.num_azimuths = 400;
  map.meta.parameters_yaml = "synthetic: true\n";
  map.meta.source_dataset = "synthetic";
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-half, half), pw(40.0, 255.0);
  for (int k = 0; k < keyframes; ++k) {
    const mrpt::math::TPose2D pose(-half / 2 + half * k / std::max(1, keyframes - 1), 0.1 * k, 0.05 * k);
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    std::vector<RadarPoint> cloud;
    auto add = [&](double wx, double wy) {
      const double dx = wx - pose.x, dy = wy - pose.y;
      RadarPoint p;
      p.x = static_cast<float>(c * dx + s * dy);
      p.y = static_cast<float>(-s * dx + c * dy);
      p.range_m = std::hypot(p.x, p.y);
      p.power = static_cast<float>(pw(rng));
      cloud.push_back(p);
    };
    for (int i = 0; i < points; ++i) add(u(rng), u(rng));
    for (double cx : {-half, half})
      for (double cy : {-half, half}) add(cx, cy);
    addKeyframe(map, 1'700'000'000'000'000'000LL + k * 250'000'000LL, pose, cloud);
  }
  return map;
}

}  // namespace radarslam::test
