#include "localize_map_dds.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>

#include <radarslam/core/errors.h>
#include <radarslam/dds/domain.h>

namespace radarslam::cli {

namespace fs = std::filesystem;

std::optional<std::uint32_t> ddsMapDomain(const std::string& map, std::uint32_t default_domain) {
  const std::string prefix = "dds:";
  if (map.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  const std::string rest = map.substr(prefix.size());
  if (rest.empty()) return default_domain;
  if (rest.size() > 3 || rest.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(
        map, "expected dds: or dds:DOMAIN (a DDS domain id 0.." + std::to_string(dds::kMaxDomainId) + ")");
  return static_cast<std::uint32_t>(std::stoul(rest));
}

FetchedMap::FetchedMap(const std::string& source, const MapFetchOptions& options) {
  const std::string xml = options.config_file.empty() ? std::string(dds::kLoopbackConfigXml)
                                                      : dds::readConfigFile(options.config_file);
  // A new directory of our own: mkdir fails if the name exists, so nothing of anyone else is used.
  std::random_device rd;
  const fs::path base = fs::temp_directory_path();
  for (int attempt = 0;; ++attempt) {
    char name[64];
    std::snprintf(name, sizeof name, "radarslam-map-%d-%08x", static_cast<int>(::getpid()), rd());
    const fs::path candidate = base / name;
    auto guard = std::make_unique<TemporaryPath>(candidate);  // registered before it exists
    if (::mkdir(candidate.c_str(), 0700) == 0) {
      dir_ = candidate;
      removed_on_signal_ = std::move(guard);
      break;
    }
    if (errno != EEXIST || attempt > 100)
      throw InputError(
          source, "cannot create a temporary directory in " + base.string() + ": " + std::strerror(errno));
  }
  try {
    dds::Domain domain(options.domain_id, xml);
    received_ = dds::receiveMapFiles(domain, dir_, {options.timeout_s, options.max_bytes}, source);
  } catch (...) {
    remove();
    throw;
  }
}

FetchedMap::~FetchedMap() { remove(); }

void FetchedMap::remove() noexcept {
  if (dir_.empty()) return;
  std::error_code ec;
  fs::remove_all(dir_, ec);  // the directory this object created, with what it wrote into it
  dir_.clear();
  removed_on_signal_.reset();
}

}  // namespace radarslam::cli
