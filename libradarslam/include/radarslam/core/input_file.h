#pragma once
// The check every input file passes before it is opened (scan files, map files, configs, trajectory
// files): it must be a regular file. open() on a FIFO blocks until a writer appears (forever, and
// a process stuck there ignores SIGTERM's clean shutdown), and reading a directory fails with
// unhelpful errors (std::bad_alloc from a size of 2^63) that do not name the file.
#include <filesystem>

namespace radarslam {

/// Throws InputError(path, ...) unless `path` is (or is a symlink to) a regular file:
/// `missing_problem` if nothing is there, "not a regular file (a directory)", "not a regular file
/// (a FIFO)", ... Uses stat(), which never opens the file, so it cannot block.
void requireRegularFile(const std::filesystem::path& path, const char* missing_problem = "file not found");

}  // namespace radarslam
