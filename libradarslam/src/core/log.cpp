#include "radarslam/core/log.h"

#include <algorithm>
#include <cctype>

#include "radarslam/core/errors.h"

namespace radarslam {

mrpt::system::COutputLogger& logger() {
  static mrpt::system::COutputLogger instance("radarslam");
  return instance;
}

mrpt::system::VerbosityLevel parseVerbosity(const std::string& name) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::toupper(c); });
  if (n == "DEBUG") return mrpt::system::LVL_DEBUG;
  if (n == "INFO") return mrpt::system::LVL_INFO;
  if (n == "WARN" || n == "WARNING") return mrpt::system::LVL_WARN;
  if (n == "ERROR") return mrpt::system::LVL_ERROR;
  throw InputError("--verbosity", "unknown level '" + name + "' (use DEBUG, INFO, WARN or ERROR)");
}

}  // namespace radarslam
