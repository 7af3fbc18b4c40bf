#pragma once
// The output rule (docs/hardening.md, "Output rule"), shared by every command that writes:
// an output only ever replaces what radarslam itself created, never overlaps an input, special
// files (devices, FIFOs, sockets) are written in place and symbolic links are written through.
// The checks run before any work starts and throw a one-line InputError naming the path.
#include <filesystem>
#include <string>

namespace radarslam {

/// `path` with the symbolic links of its last component followed (chains, relative targets) and
/// a trailing '/' dropped: an output written through a link replaces what the link points to.
std::filesystem::path followSymlinks(const std::filesystem::path& path);

/// True if `path` (links followed) is a character or block device, a FIFO or a socket.
bool isSpecialFile(const std::filesystem::path& path);

/// A file output (-o FILE, --json FILE): a file name whose parent is (or can be created as) a
/// directory. An existing regular file is replaced atomically, a special file written in place;
/// a directory is refused. `option` names the argument in the message for an empty path.
void checkFileOutput(const std::filesystem::path& path, const std::string& option = "-o");

/// A map directory output (-o MAP): missing, or a map directory (manifest.yaml) to be replaced.
/// With `force` also an empty directory or a regular file. A non-empty directory that is not a map
/// is always refused: its contents are never deleted.
void checkMapOutput(const std::filesystem::path& dir, bool force, const std::string& option = "-o");

/// A directory that receives files by name (--eval-dir, --plot-dir, export -o): missing (it is
/// created) or a directory.
void checkDirectoryOutput(const std::filesystem::path& dir, const std::string& option);

/// Refuses an output equal to `input`, inside it or containing it (absolute paths, symbolic links
/// resolved). `allow_inside`: an output inside `input` is fine (export's default MAP/exports).
void checkNoOverlap(const std::filesystem::path& input, const std::filesystem::path& output,
                    bool allow_inside = false);

/// Refuses two outputs of one run naming the same file (absolute paths, symbolic links resolved):
/// the second would replace the first. `option` names the second in the message.
void checkDistinctOutputs(const std::filesystem::path& first, const std::filesystem::path& second,
                          const std::string& option);

/// "<parent>/.<name>.<tag>.<pid>": a hidden sibling of `path` to build a directory output in
/// before it is renamed into place.
std::filesystem::path stagingSibling(const std::filesystem::path& path, const std::string& tag);

}  // namespace radarslam
