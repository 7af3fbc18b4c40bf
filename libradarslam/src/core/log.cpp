#include "radarslam/core/log.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "radarslam/core/errors.h"

namespace radarslam {

namespace {
// All log lines go to stderr, so stdout carries only a program's own output (summaries, data).
void printToStderr(std::string_view msg, mrpt::system::VerbosityLevel level, std::string_view name,
                   const mrpt::Clock::time_point&) {
  static const char* const kLevel[] = {"DEBUG", "INFO", "WARN", "ERROR"};
  const int idx = std::clamp(static_cast<int>(level), 0, 3);
  std::string text(msg);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  std::fprintf(stderr, "[%.*s] %s: %s\n", static_cast<int>(name.size()), name.data(), kLevel[idx],
               text.c_str());
}
}  // namespace

mrpt::system::COutputLogger& logger() {
  static mrpt::system::COutputLogger instance("radarslam");
  static const bool configured = [] {
    instance.logging_enable_console_output = false;
    instance.logRegisterCallback(&printToStderr);
    return true;
  }();
  (void)configured;
  return instance;
}

mrpt::system::VerbosityLevel parseVerbosity(const std::string& name) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::toupper(c); });
  if (n == "DEBUG") return mrpt::system::LVL_DEBUG;
  if (n == "INFO") return mrpt::system::LVL_INFO;
  if (n == "WARN" || n == "WARNING") return mrpt::system::LVL_WARN;
  if (n == "ERROR") return mrpt::system::LVL_ERROR;
  throw InputError("--verbosity", "unknown level '" + name + "' (use DEBUG, INFO, WARN or ERROR)");
}

}  // namespace radarslam
