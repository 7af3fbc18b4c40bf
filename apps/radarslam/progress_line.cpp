#include "progress_line.h"

#include <unistd.h>

#include <cstdio>
#include <utility>

#include "dataset_config.h"  // clockText

namespace radarslam::cli {

ProgressLine::ProgressLine(std::string what, std::size_t total, bool enabled, std::string unit,
                           std::string rate_unit)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      rate_unit_(rate_unit.empty() ? unit_ : std::move(rate_unit)),
      total_(total),
      enabled_(enabled),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(Clock::now()),
      last_(start_) {}

double ProgressLine::elapsedSeconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void ProgressLine::update(std::size_t done, const Tail& tail) {
  if (!enabled_ || finished_) return;
  const auto now = Clock::now();
  const double interval = tty_ ? 0.5 : 10.0;
  if (std::chrono::duration<double>(now - last_).count() < interval) return;
  last_ = now;
  print(done, tail, false, now);
}

void ProgressLine::finish(std::size_t done, const Tail& tail, std::optional<Clock::time_point> end) {
  if (!enabled_ || finished_) return;
  finished_ = true;
  print(done, tail, true, end ? *end : Clock::now());
}

void ProgressLine::print(std::size_t done, const Tail& tail, bool final, Clock::time_point at) {
  const double el = std::chrono::duration<double>(at - start_).count();
  const double rate = el > 0 ? static_cast<double>(done) / el : 0.0;
  std::string line = what_ + ": " + std::to_string(done);
  char buf[128];
  if (total_ > 0) {
    const double left = done < total_ ? static_cast<double>(total_ - done) : 0.0;
    std::snprintf(buf, sizeof buf, "/%zu %s (%.0f%%), %.1f %s/s, ETA %s", total_, unit_.c_str(),
                  100.0 * static_cast<double>(done) / static_cast<double>(total_), rate, rate_unit_.c_str(),
                  clockText(rate > 0 ? left / rate : 0.0).c_str());
  } else {
    std::snprintf(buf, sizeof buf, " %s, %.1f %s/s", unit_.c_str(), rate, rate_unit_.c_str());
  }
  line += buf;
  if (final) {
    std::snprintf(buf, sizeof buf, ", %s elapsed", clockText(el).c_str());
    line += buf;
  }
  if (tail) {
    const std::string t = tail();
    if (!t.empty()) line += ", " + t;
  }
  if (tty_)
    std::fprintf(stderr, "\r%s   %s", line.c_str(), final ? "\n" : "");
  else
    std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
  printed_ = true;
}

}  // namespace radarslam::cli
