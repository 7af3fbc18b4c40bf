#pragma once
// The version of radarslam and the git revision it was built from (`--version` of every program,
// the map manifest's software_version).
#include <string>

namespace radarslam {

/// The CMake project version, e.g. "0.1.0".
const char* versionNumber();
/// The git revision of the source tree at build time: 12 hex digits, "-dirty" if it had
/// uncommitted changes, "unknown" if it was not a git checkout.
const char* gitRevision();
/// "0.1.0 (git 1a2b3c4d5e6f)".
std::string versionText();

}  // namespace radarslam
