#include "radarslam/core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "radarslam/core/errors.h"

namespace radarslam {

namespace {
const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a file";
}
}  // namespace

void requireRegularFile(const std::filesystem::path& path, const char* missing_problem) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) throw InputError(path.string(), missing_problem);
    throw InputError(path.string(), std::string("cannot access the file: ") + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode))
    throw InputError(path.string(), std::string("not a regular file (") + kindOf(st.st_mode) + ")");
}

}  // namespace radarslam
