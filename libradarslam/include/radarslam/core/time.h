#pragma once
// Time in radarslam: int64 nanoseconds since the UNIX epoch (UTC) everywhere in our own data.
// Datasets stamp in microseconds (Oxford, Boreas) or nanoseconds (MulRan, RADIATE); readers
// convert on entry. MRPT observations carry mrpt::Clock time points (100 ns ticks); convert here.
#include <mrpt/core/Clock.h>

#include <cstdint>
#include <string>

namespace radarslam {

using StampNs = std::int64_t;

constexpr StampNs kNsPerUs = 1000;
constexpr StampNs kNsPerSec = 1'000'000'000;

inline double toSeconds(StampNs t) { return static_cast<double>(t) * 1e-9; }

/// Exact to MRPT's 100 ns tick.
mrpt::Clock::time_point toMrptTime(StampNs t);
StampNs fromMrptTime(mrpt::Clock::time_point t);

/// Parses an integer UNIX timestamp whose unit is inferred from its digit count, as the datasets
/// need (pyboreas does the same): <= 10 digits seconds, 13 ms, 16 us, 19 ns. Leading zeros and
/// a leading '+' are ignored. Returns false on anything that is not such a number.
bool parseStampByDigits(const std::string& text, StampNs& out);

/// "1574859771.744660272" (RADIATE: seconds, '.', nanosecond count written without zero padding,
/// so a fraction shorter than 9 digits is left-padded as the RADIATE SDK does) to ns.
bool parseSecondsDotFraction(const std::string& text, StampNs& out);

}  // namespace radarslam
