#pragma once
// Runs the `radarslam` program (RADARSLAM_CLI) through the shell for the CLI tests, with its
// stdout and stderr captured in files of a test directory.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "file_contents.h"
#include "temp_dir.h"

namespace radarslam::test {

struct CliResult {
  int code = -1;  ///< exit code (-1 if killed by a signal)
  std::string out, err;
};

/// Runs the shell command line `command` (arguments shell-quoted by the caller) with its stdout
/// and stderr captured in stdout.txt and stderr.txt of `dir`.
inline CliResult runCommand(const std::string& command, const std::filesystem::path& dir) {
  const auto out_file = dir / "stdout.txt", err_file = dir / "stderr.txt";
  const std::string cmd = command + " > '" + out_file.string() + "' 2> '" + err_file.string() + "'";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readFileBytes(out_file);
  r.err = readFileBytes(err_file);
  return r;
}

/// `radarslam ARGS` (ARGS shell-quoted by the caller); stdout.txt and stderr.txt go to `dir`.
inline CliResult runCli(const std::string& args, const std::filesystem::path& dir) {
  return runCommand(std::string(RADARSLAM_CLI) + " " + args, dir);
}

inline CliResult runCli(const std::string& args, const TempDir& tmp) { return runCli(args, tmp.path()); }

/// `path` in single quotes for a shell command line (the tests' paths hold no quote).
inline std::string shellQuoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

}  // namespace radarslam::test
