#pragma once
// Locating the real radar data in ../shared (never copied into the project; licences).
// Without it a test skips with a clear message - but when CI is set, it fails instead, so CI
// can never pass by silently skipping the real-data tests.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace radarslam::test {

inline std::filesystem::path sharedDir() {
  if (const char* env = std::getenv("RADARSLAM_SHARED_DIR")) return env;
  return RADARSLAM_SHARED_DIR;
}

inline std::filesystem::path realDataDir() { return sharedDir() / "data" / "real"; }

inline bool inCI() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) != "" && std::string(ci) != "0" && std::string(ci) != "false";
}

}  // namespace radarslam::test

/// Use at the top of a test: sets `var` to ../shared/data/real/<sub> or skips/fails.
#define RADARSLAM_REQUIRE_REAL_DATA(var, sub)                                             \
  const std::filesystem::path var = ::radarslam::test::realDataDir() / (sub);             \
  if (!std::filesystem::exists(var)) {                                                    \
    if (::radarslam::test::inCI()) FAIL() << "real data missing in CI: " << var;          \
    GTEST_SKIP() << "real data not found at " << var                                      \
                 << " (clone the project next to ../shared or set RADARSLAM_SHARED_DIR)"; \
  }
