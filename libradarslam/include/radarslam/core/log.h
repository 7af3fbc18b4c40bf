#pragma once
// Logging goes through MRPT's logger. One process-wide logger named "radarslam"; programs set
// its level (--verbosity) and library code logs through it.
#include <mrpt/system/COutputLogger.h>

namespace radarslam {

mrpt::system::COutputLogger& logger();

/// Parses "DEBUG", "INFO", "WARN", "ERROR" (case-insensitive). Throws InputError otherwise.
mrpt::system::VerbosityLevel parseVerbosity(const std::string& name);

}  // namespace radarslam
