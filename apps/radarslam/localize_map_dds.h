#pragma once
// `radarslam localize dds:[DOMAIN] DIR ...` (docs/dds.md, "The map files layer"): the map comes
// from a radarslam-map-server's rt/radarslam/map_files instead of a directory. Its files are
// received and checked into a private temporary directory this program creates (and removes
// afterwards, also on SIGINT/SIGTERM), which is then loaded with the normal map loader.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <radarslam/core/cleanup_on_signal.h>
#include <radarslam/dds/map_file_receiver.h>

namespace radarslam::cli {

/// MAP = "dds:" -> `default_domain` (--domain); "dds:N" -> N; nullopt if MAP is not a DDS source.
/// Throws InputError(MAP, ...) for "dds:" followed by anything but a domain number.
std::optional<std::uint32_t> ddsMapDomain(const std::string& map, std::uint32_t default_domain);

struct MapFetchOptions {
  std::uint32_t domain_id = 0;
  std::string config_file;                           ///< --dds-config (empty: built-in loopback XML)
  double timeout_s = 30.0;                           ///< --map-timeout
  std::uint64_t max_bytes = std::uint64_t{4} << 30;  ///< --map-max-mb
};

/// A map received over DDS into a fresh private directory (mode 0700 under $TMPDIR); the
/// destructor removes that directory and nothing else.
class FetchedMap {
 public:
  /// Blocks until the newest map publication is complete and checked. Throws InputError(source,
  /// problem) on timeout or on a bad chunk (the directory is removed first).
  FetchedMap(const std::string& source, const MapFetchOptions& options);
  ~FetchedMap();
  FetchedMap(const FetchedMap&) = delete;
  FetchedMap& operator=(const FetchedMap&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  const dds::ReceivedMapFiles& received() const { return received_; }

 private:
  void remove() noexcept;
  std::filesystem::path dir_;
  std::unique_ptr<TemporaryPath> removed_on_signal_;
  dds::ReceivedMapFiles received_;
};

}  // namespace radarslam::cli
