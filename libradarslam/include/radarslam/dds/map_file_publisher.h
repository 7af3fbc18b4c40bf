#pragma once
// The map files layer (docs/dds.md, "The map files layer"): a saved map's manifest.yaml and the
// files it lists, sent as radarslam/MapFileChunk samples on rt/radarslam/map_files, latched (RELIABLE,
// TRANSIENT_LOCAL, KEEP_LAST = every chunk of the publication), so a localiser on another host can
// rebuild the map directory (dds/map_file_receiver.h). Files are checked against the manifest
// before anything is sent and streamed one chunk at a time (never a whole file in memory).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "radarslam/core/time.h"
#include "radarslam/dds/messages.h"

namespace radarslam::dds {

class Domain;
template <class Msg>
class Publisher;

/// Receivers reject a chunk with more data than this (hostile sizes).
inline constexpr std::size_t kMaxMapFileChunkBytes = std::size_t{64} << 20;

struct MapFilesParams {
  std::size_t chunk_bytes = std::size_t{4} << 20;  ///< data per sample (1 .. kMaxMapFileChunkBytes)
  /// Also the layer files (layers/*): they have their own topics and loadMap does not read them.
  bool with_layers = false;
};

/// What every chunk of one publication repeats.
struct MapFilesPublication {
  std::string map_name;
  std::uint32_t revision = 0;
  StampNs stamp = 0;
  /// SHA-256 (hex) the manifest.yaml must have (the one the server's load started with; the map
  /// changed if it differs); empty: no check.
  std::string manifest_sha256;
};

struct MapFilesSummary {
  std::size_t files = 0, chunks = 0;
  std::uint64_t bytes = 0;
};

/// The chunks of one publication of `map_dir`, one at a time, as MapFilesPublisher sends them:
/// every file is checked first (see publish()), then `start` gets the totals and `fn` each chunk
/// (manifest.yaml first, then the manifest's files in order). Returns the totals. Throws as publish().
MapFilesSummary forEachMapFileChunk(const std::filesystem::path& map_dir,
                                    const MapFilesPublication& publication, const MapFilesParams& params,
                                    const std::function<void(const MapFilesSummary&)>& start,
                                    const std::function<void(const MapFileChunkMsg&)>& fn);

class MapFilesPublisher {
 public:
  MapFilesPublisher(Domain& domain, MapFilesParams params = {});
  ~MapFilesPublisher();
  MapFilesPublisher(const MapFilesPublisher&) = delete;
  MapFilesPublisher& operator=(const MapFilesPublisher&) = delete;

  /// Checks every file (regular file, size and SHA-256 as the manifest says; manifest.yaml's SHA-256
  /// = publication.manifest_sha256), then replaces the previous publication by this one: the
  /// manifest first (file 0), then the files in the manifest's order. Throws InputError naming the
  /// file; if a check fails nothing is sent and the previous publication stays. A file that
  /// changes while it is sent (the map is being swapped) withdraws the publication and throws.
  MapFilesSummary publish(const std::filesystem::path& map_dir, const MapFilesPublication& publication);
  /// Number of matched subscriptions right now (0 before the first publish).
  std::uint32_t matchedSubscriptions() const;

 private:
  Domain& domain_;
  MapFilesParams params_;
  std::unique_ptr<Publisher<MapFileChunkMsg>> writer_;
};

}  // namespace radarslam::dds
