#include "radarslam/core/time.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>

namespace radarslam {

namespace {
// mrpt::Clock counts 100 ns ticks since 1601-01-01 (Windows FILETIME epoch).
constexpr std::int64_t kUnixEpochInMrptTicks = 116444736000000000LL;

bool allDigits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}
}  // namespace

mrpt::Clock::time_point toMrptTime(StampNs t) {
  return mrpt::Clock::time_point(mrpt::Clock::duration(t / 100 + kUnixEpochInMrptTicks));
}

StampNs fromMrptTime(mrpt::Clock::time_point t) {
  return (t.time_since_epoch().count() - kUnixEpochInMrptTicks) * 100;
}

bool parseStampByDigits(const std::string& text, StampNs& out) {
  std::string s = text;
  if (!s.empty() && s.front() == '+') s.erase(0, 1);
  if (!allDigits(s) || s.size() > 19) return false;
  const std::size_t significant = s.size() - std::min(s.find_first_not_of('0'), s.size());
  // <= 19 digits fit in uint64; a value whose ns count overflows int64 is not a stamp (fuzzing).
  const std::uint64_t v = std::stoull(s);
  const std::int64_t unit = significant <= 10   ? kNsPerSec
                            : significant <= 13 ? 1'000'000
                            : significant <= 16 ? kNsPerUs
                                                : 1;
  if (v > static_cast<std::uint64_t>(std::numeric_limits<StampNs>::max() / unit)) return false;
  out = static_cast<StampNs>(v) * unit;
  return true;
}

bool parseSecondsDotFraction(const std::string& text, StampNs& out) {
  const auto dot = text.find('.');
  const std::string whole = text.substr(0, dot);
  std::string frac = dot == std::string::npos ? "" : text.substr(dot + 1);
  if (!allDigits(whole) || whole.size() > 10 || (dot != std::string::npos && !allDigits(frac)) ||
      frac.size() > 9)
    return false;
  // RADIATE writes the nanosecond count without zero padding ("771.44660272" = 771.044660272 s);
  // its SDK left-pads the fraction to 9 digits, and so do we.
  frac.insert(0, 9 - frac.size(), '0');
  const std::int64_t seconds = std::stoll(whole);
  if (seconds > std::numeric_limits<StampNs>::max() / kNsPerSec - 1) return false;  // int64 ns overflow
  out = seconds * kNsPerSec + std::stoll(frac);
  return true;
}

}  // namespace radarslam
