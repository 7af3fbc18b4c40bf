#pragma once
// Runs a function with file descriptor 2 redirected to a temporary file and returns what was
// written there. MRPT's YAML parser (libfyaml) prints its diagnostics to stderr instead of
// putting them in the exception, and on some syntax errors returns a half-parsed document without
// throwing at all; capturing them lets YamlParams turn them into one error line of our own.
// Process-wide (fd 2 is shared): calls are serialised, and are meant for start-up code.
#include <exception>
#include <functional>
#include <string>

namespace radarslam::detail {

struct Captured {
  std::string output;        ///< what `fn` wrote to fd 2
  std::exception_ptr error;  ///< what `fn` threw, if anything
};

/// Calls `fn` with fd 2 redirected; restores fd 2 before returning.
Captured captureStderr(const std::function<void()>& fn);

}  // namespace radarslam::detail
