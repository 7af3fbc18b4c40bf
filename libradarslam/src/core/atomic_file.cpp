#include "radarslam/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "radarslam/core/cleanup_on_signal.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/output_path.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {
fs::path temporarySibling(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  // Built with append(): GCC 12 reports a false -Wrestrict for `"." + std::string`.
  std::string name(1, '.');
  name.append(path.filename().string()).append(".tmp.").append(std::to_string(::getpid()));
  name.append(".").append(std::to_string(counter++));
  return path.parent_path() / name;
}

void fsyncDirectory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;  // best effort: some filesystems do not allow opening directories
  ::fsync(fd);
  ::close(fd);
}
}  // namespace

void fsyncFile(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw InputError(path.string(), std::string("cannot open for fsync: ") + std::strerror(errno));
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw InputError(path.string(), std::string("fsync failed: ") + std::strerror(errno));
}

void writeFileAtomically(const fs::path& path_in, const std::function<void(const fs::path& tmp)>& write) {
  if (path_in.empty()) throw InputError("output", "empty output path");
  // Through a symbolic link: the file it points to is replaced, the link stays.
  const fs::path path = followSymlinks(path_in);
  if (isSpecialFile(path)) {  // a device, FIFO or socket is written in place, never renamed over
    write(path);
    return;
  }
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw InputError(path.parent_path().string(), "cannot create directory: " + ec.message());
  }
  const fs::path tmp = temporarySibling(path);
  const TemporaryPath removed_on_signal(tmp);
  try {
    write(tmp);
    if (!fs::exists(tmp)) throw InputError(path_in.string(), "writer produced no output");
    fsyncFile(tmp);
    fs::rename(tmp, path, ec);
    if (ec) throw InputError(path_in.string(), "cannot rename temporary file into place: " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fsyncDirectory(path.parent_path());
}

void writeBytesAtomically(const fs::path& path, std::span<const unsigned char> bytes) {
  writeFileAtomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw InputError(path.string(), "write failed (disk full?)");
  });
}

void writeTextAtomically(const fs::path& path, std::string_view text) {
  writeBytesAtomically(path, {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

}  // namespace radarslam
