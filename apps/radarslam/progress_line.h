#pragma once
// The progress line every long-running command prints on stderr: count, percentage, rate, ETA and
// a command-specific tail. On a terminal it is one line rewritten in place ('\r') about twice a
// second; when stderr is a file or a pipe (CI logs, `2> log`) it is a whole line every ~10 s and
// at the end, never a '\r'.
#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

namespace radarslam::cli {

class ProgressLine {
 public:
  /// `what` names the command ("map"); `total` is the number of items (0: unknown, e.g. a live
  /// stream: no percentage, no ETA); `enabled` false (e.g. --quiet) prints nothing. `unit` follows
  /// the count ("12 DDS scans"), `rate_unit` (default: `unit`) the rate ("3.9 scans/s").
  ProgressLine(std::string what, std::size_t total, bool enabled = true, std::string unit = "scans",
               std::string rate_unit = "");
  using Clock = std::chrono::steady_clock;
  using Tail = std::function<std::string()>;  ///< the command's own figures, built only when printed
  /// Prints if the refresh interval has passed since the last line.
  void update(std::size_t done, const Tail& tail = {});
  /// Prints the final state (always) and ends the line. Rate and elapsed time are measured up to
  /// `end` if given (e.g. the last scan of a stream that ended with a timeout), else up to now.
  void finish(std::size_t done, const Tail& tail = {}, std::optional<Clock::time_point> end = {});
  double elapsedSeconds() const;
  bool toTerminal() const { return tty_; }

 private:
  void print(std::size_t done, const Tail& tail, bool final, Clock::time_point at);
  std::string what_, unit_, rate_unit_;
  std::size_t total_;
  bool enabled_, tty_;
  Clock::time_point start_, last_;
  bool printed_ = false, finished_ = false;
};

}  // namespace radarslam::cli
