#pragma once
// Receives the map files layer (rt/radarslam/map_files) into a directory: the newest publication a
// radarslam-map-server offers, every file checked (dds/map_file_assembler.h), ready for loadMap.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace radarslam::dds {

class Domain;

struct MapReceiveParams {
  double timeout_s = 30.0;  ///< give up when no complete map arrived within this time
  /// A publication whose files add up to more bytes is refused before anything more is written:
  /// a hostile publisher on the domain must not fill the disk.
  std::uint64_t max_bytes = std::uint64_t{4} << 30;
};

struct ReceivedMapFiles {
  std::string map_name;
  std::uint32_t revision = 0;
  std::size_t files = 0, chunks = 0;
  std::uint64_t bytes = 0;
  double seconds = 0;  ///< from the subscription's creation to the last chunk
};

/// Subscribes on `domain` (RELIABLE, TRANSIENT_LOCAL, KEEP_ALL) and writes the files of the newest
/// publication seen into `dir` (existing, empty, private to the caller). Throws InputError(source,
/// problem) on a hostile or inconsistent chunk, or when no complete map arrived within the timeout
/// (naming what was received).
ReceivedMapFiles receiveMapFiles(Domain& domain, const std::filesystem::path& dir,
                                 const MapReceiveParams& params, const std::string& source);

}  // namespace radarslam::dds
