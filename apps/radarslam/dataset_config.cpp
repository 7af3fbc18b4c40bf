#include "dataset_config.h"

#include <cstdio>
#include <cstdlib>

namespace radarslam::cli {

namespace fs = std::filesystem;

std::string defaultConfigName(DatasetKind kind) {
  switch (kind) {
    case DatasetKind::Oxford:
      return "oxford.yaml";
    case DatasetKind::MulRanOxfordForm:
    case DatasetKind::MulRanPolar:
      return "mulran.yaml";
    case DatasetKind::Boreas:
      return "boreas.yaml";
    case DatasetKind::Radiate:
      return "radiate.yaml";
    case DatasetKind::Rawlog:
      return "";
  }
  return "";
}

fs::path groundTruthFile(const DatasetReader& reader) {
  switch (reader.kind()) {
    case DatasetKind::Oxford:
      return reader.root() / "gt" / "radar_odometry.csv";
    case DatasetKind::MulRanOxfordForm:
    case DatasetKind::MulRanPolar:
      return reader.root() / "global_pose.csv";
    case DatasetKind::Boreas:
      return reader.root() / "applanix" / "radar_poses.csv";
    case DatasetKind::Radiate:
    case DatasetKind::Rawlog:
      break;
  }
  return reader.root();
}

std::optional<fs::path> findConfig(const std::string& explicit_path, DatasetKind kind) {
  if (!explicit_path.empty()) return fs::path(explicit_path);
  return findConfigFile(defaultConfigName(kind));
}

std::optional<fs::path> findConfigFile(const std::string& name) {
  if (name.empty()) return std::nullopt;
  if (const char* env = std::getenv("RADARSLAM_CONFIG_DIR")) {
    if (fs::exists(fs::path(env) / name)) return fs::path(env) / name;
  }
  std::error_code ec;
  fs::path dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  // Installed: <prefix>/bin/radarslam -> <prefix>/share/radarslam/config (cmake/Install.cmake).
  if (!ec && fs::exists(dir.parent_path() / "share" / "radarslam" / "config" / name))
    return dir.parent_path() / "share" / "radarslam" / "config" / name;
  // In a build tree: build/apps/radarslam -> config/ of the source tree above it.
  for (int up = 0; up < 5 && !ec && !dir.empty(); ++up, dir = dir.parent_path()) {
    if (fs::exists(dir / "config" / name)) return dir / "config" / name;
    if (dir == dir.parent_path()) break;
  }
  return std::nullopt;
}

std::string clockText(double s) {
  char buf[32];
  const long t = static_cast<long>(s + 0.5);
  std::snprintf(buf, sizeof buf, "%ld:%02ld", t / 60, t % 60);
  return buf;
}

}  // namespace radarslam::cli
