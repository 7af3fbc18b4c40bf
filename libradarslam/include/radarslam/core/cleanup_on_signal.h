#pragma once
// Temporary outputs removed when the process is interrupted. Writers register a temporary file or
// directory (TemporaryPath) for as long as it exists; after installCleanupOnSignal() (once, in
// main) SIGINT, SIGTERM and SIGHUP remove every registered path and then end the process by the
// same signal, as without the handler. The handler itself only writes to a pipe
// (async-signal-safe); the removal runs on a thread of its own.
#include <cstdint>
#include <filesystem>

namespace radarslam {

/// Installs the handlers (idempotent). Signals that are ignored (nohup, background jobs) stay
/// ignored.
void installCleanupOnSignal();

/// Registers `path` (a file, or a directory removed with its contents) while in scope; the
/// destructor only unregisters. Register before creating the path.
class TemporaryPath {
 public:
  explicit TemporaryPath(const std::filesystem::path& path);
  ~TemporaryPath();
  TemporaryPath(const TemporaryPath&) = delete;
  TemporaryPath& operator=(const TemporaryPath&) = delete;

 private:
  std::uint64_t id_;
};

}  // namespace radarslam
