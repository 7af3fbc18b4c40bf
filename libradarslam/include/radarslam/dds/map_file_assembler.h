#pragma once
// Reassembles the map files layer (rt/radarslam/map_files, dds/map_file_publisher.h) into a
// directory. Every chunk is hostile input until checked: paths must be relative names of map files
// (no "..", no absolute path, only [A-Za-z0-9._-] per component, at most one subdirectory), all
// chunks of a publication must agree on what they describe, each chunk arrives once, the chunks of
// a file must tile it exactly, and each file must have the size and SHA-256 its chunks state and
// the received manifest lists. Data is written to disk as it arrives (one chunk in memory).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "radarslam/core/time.h"
#include "radarslam/dds/messages.h"

namespace radarslam::dds {

/// Empty if `path` is an acceptable map file path, else the problem (for the one-line error).
std::string mapFilePathProblem(const std::string& path);

class MapFileAssembler {
 public:
  /// `dir`: an existing directory private to the caller (files are created only inside it);
  /// `source`: names the input in errors (InputError(source, problem)); `max_bytes`: a publication
  /// whose files (their stated sizes, summed as they appear) exceed it is refused.
  MapFileAssembler(std::filesystem::path dir, std::string source,
                   std::uint64_t max_bytes = std::uint64_t{4} << 30);

  /// Takes one chunk. Chunks of an older publication than the one being assembled (lower revision,
  /// or equal revision and older stamp) are ignored; one of a newer publication discards the files
  /// written so far and starts over. Returns true once every file of the publication is complete
  /// and checked (further chunks are then ignored). Throws InputError(source, problem) for a chunk
  /// that is malformed or inconsistent with the publication (the problem names the file).
  bool add(const MapFileChunkMsg& chunk);

  bool complete() const { return complete_; }
  const std::string& mapName() const { return pub_.map_name; }
  std::uint32_t revision() const { return pub_.revision; }
  std::uint32_t totalChunks() const { return pub_.total_chunks; }
  std::size_t chunksReceived() const { return chunks_; }
  std::size_t chunksIgnored() const { return ignored_; }
  std::uint64_t bytesReceived() const { return bytes_; }
  std::size_t filesComplete() const;

 private:
  struct FileState {
    std::uint32_t index = 0;
    std::uint64_t size = 0;
    std::string sha256;
    std::uint32_t chunk_count = 0;
    std::map<std::uint32_t, std::pair<std::uint64_t, std::uint64_t>> chunks;  // index -> (offset, bytes)
    bool complete = false;
  };
  [[noreturn]] void fail(const std::string& problem) const;
  void reset(const MapFileChunkMsg& first);
  void checkSamePublication(const MapFileChunkMsg& c) const;
  void finishFile(const std::string& path, FileState& f);
  void checkAgainstManifest(const std::string& path, const FileState& f) const;

  std::filesystem::path dir_;
  std::string source_;
  bool started_ = false, complete_ = false;
  MapFileChunkMsg pub_;  // the publication's fields (data empty)
  StampNs stamp_ = 0;
  std::map<std::string, FileState> files_;                                 // by path
  std::map<std::string, std::pair<std::uint64_t, std::string>> manifest_;  // listed files: size, sha
  bool manifest_read_ = false;
  std::size_t chunks_ = 0, ignored_ = 0;
  std::uint64_t bytes_ = 0;
  std::uint64_t max_bytes_;
  std::uint64_t stated_bytes_ = 0;  ///< sum of the stated sizes of the files seen
};

}  // namespace radarslam::dds
