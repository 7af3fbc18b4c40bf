#pragma once
// Helpers shared by the subcommands: TCLAP set-up with the common options (--verbosity), and
// parsing that turns TCLAP's errors into our one-line errors.
#include <tclap/CmdLine.h>

#include <cstddef>
#include <cstdio>
#include <string>

namespace radarslam::cli {

/// Scans a command decodes ahead of its pipeline in a background thread (ScanIterator's prefetch):
/// decoding (~10 ms per Oxford PNG) overlaps the work on the previous scans. 4 scans of the largest
/// sensor (RAS6, 2.7 MB) hold 11 MB.
constexpr std::size_t kPrefetchScans = 4;

/// printf-style formatting into a string (at most 511 characters: one CSV row or report line).
template <typename... Args>
std::string formatText(const char* format, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, format, args...);
  return buf;
}

/// A TCLAP command line with radarslam's conventions: --help, --version, and --verbosity
/// (DEBUG|INFO|WARN|ERROR, default INFO) applied to the radarslam logger on parse().
class CommandLine {
 public:
  CommandLine(const std::string& name, const std::string& description);
  TCLAP::CmdLine& tclap() { return cmd_; }
  /// Parses or throws InputError("radarslam <name>", "<what is wrong>"). --help/--version print
  /// and exit(0) as usual.
  void parse(int argc, char** argv);

 private:
  std::string name_;
  TCLAP::CmdLine cmd_;
  TCLAP::ValueArg<std::string> verbosity_;
};

}  // namespace radarslam::cli
