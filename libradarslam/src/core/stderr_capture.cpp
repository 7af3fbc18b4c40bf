#include "stderr_capture.h"

#include <unistd.h>

#include <cstdio>
#include <mutex>

namespace radarslam::detail {

Captured captureStderr(const std::function<void()>& fn) {
  static std::mutex mutex;
  const std::lock_guard lock(mutex);
  Captured result;
  std::fflush(stderr);
  std::FILE* tmp = std::tmpfile();
  const int saved = tmp != nullptr ? ::dup(2) : -1;
  if (saved < 0 || ::dup2(::fileno(tmp), 2) < 0) {  // cannot capture: run uncaptured
    if (saved >= 0) ::close(saved);
    if (tmp != nullptr) std::fclose(tmp);
    try {
      fn();
    } catch (...) {
      result.error = std::current_exception();
    }
    return result;
  }
  try {
    fn();
  } catch (...) {
    result.error = std::current_exception();
  }
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::rewind(tmp);
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, tmp)) > 0;) result.output.append(buf, n);
  std::fclose(tmp);
  return result;
}

}  // namespace radarslam::detail
