#include "radarslam/core/version.h"

#include "radarslam_git_revision.h"  // generated at build time (cmake/GitRevision.cmake)

namespace radarslam {

const char* versionNumber() { return RADARSLAM_PROJECT_VERSION; }
const char* gitRevision() { return RADARSLAM_GIT_REVISION; }
std::string versionText() { return std::string(versionNumber()) + " (git " + gitRevision() + ")"; }

}  // namespace radarslam
