#pragma once
// Atomic output: a file is written to a temporary sibling, flushed to disk (fsync) and renamed
// over the destination, so readers see either the old complete file or the new complete file.
#include <filesystem>
#include <functional>
#include <span>
#include <string_view>

namespace radarslam {

/// Calls `write(tmp)` to produce the content in a temporary file next to `path`, then fsyncs and
/// renames it to `path`. If `write` throws, the temporary is removed and `path` is untouched.
/// Parent directories are created. Throws InputError naming `path` on I/O failure. A symbolic link
/// is written through (its target is replaced); a special file (device, FIFO, socket) is passed to
/// `write` itself and written in place. The temporary is removed if the process is interrupted
/// (cleanup_on_signal.h).
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& write);

void writeTextAtomically(const std::filesystem::path& path, std::string_view text);
void writeBytesAtomically(const std::filesystem::path& path, std::span<const unsigned char> bytes);

/// Flushes a written file's data to disk. Throws InputError on failure.
void fsyncFile(const std::filesystem::path& path);

}  // namespace radarslam
