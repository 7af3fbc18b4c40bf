// Dataset kind from the directory layout (FORMATS.md section 5).
#include <string>

#include "radarslam/core/errors.h"
#include "readers.h"

namespace radarslam {

namespace {
namespace fs = std::filesystem;

bool isDir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}
bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

const char* kExpected =
    "expected radar/ + radar.timestamps (Oxford), polar_oxford_form/ or sensor_data/radar/polar/ (MulRan), "
    "radar/ + applanix/ (Boreas), Navtech_Polar/ + Navtech_Polar.txt (RADIATE), or a .rawlog file";
}  // namespace

std::string toString(DatasetKind kind) {
  switch (kind) {
    case DatasetKind::Oxford:
      return "Oxford Radar RobotCar";
    case DatasetKind::MulRanOxfordForm:
      return "MulRan (polar_oxford_form)";
    case DatasetKind::MulRanPolar:
      return "MulRan (sensor_data/radar/polar)";
    case DatasetKind::Boreas:
      return "Boreas";
    case DatasetKind::Radiate:
      return "RADIATE";
    case DatasetKind::Rawlog:
      return "MRPT rawlog";
  }
  return "unknown";
}

DatasetKind detectDatasetKind(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path.string(), "no such file or directory");
  if (isFile(path)) {
    if (path.extension() == ".rawlog") return DatasetKind::Rawlog;
    throw InputError(path.string(),
                     std::string("unknown dataset layout: a file that is not a .rawlog; ") + kExpected);
  }
  if (!isDir(path)) throw InputError(path.string(), "not a directory or regular file");
  if (fs::directory_iterator(path, ec) == fs::directory_iterator())
    throw InputError(path.string(), std::string("empty directory; ") + kExpected);
  if (isDir(path / "radar") && isFile(path / "radar.timestamps")) return DatasetKind::Oxford;
  if (isDir(path / "polar_oxford_form")) return DatasetKind::MulRanOxfordForm;
  if (isDir(path / "sensor_data" / "radar" / "polar")) return DatasetKind::MulRanPolar;
  if (isDir(path / "radar") && (isDir(path / "applanix") || isDir(path / "calib")))
    return DatasetKind::Boreas;
  if (isDir(path / "Navtech_Polar")) {
    if (!isFile(path / "Navtech_Polar.txt"))
      throw InputError((path / "Navtech_Polar.txt").string(),
                       "missing RADIATE frame times (Navtech_Polar.txt)");
    return DatasetKind::Radiate;
  }
  if (isDir(path / "radar"))
    throw InputError(
        (path / "radar.timestamps").string(),
        "missing radar.timestamps: radar/ needs radar.timestamps (Oxford) or applanix/ (Boreas)");
  throw InputError(path.string(), std::string("unknown dataset layout; ") + kExpected);
}

namespace io_detail {
std::optional<fs::path> datasetRootOfScanFile(const fs::path& scan_file) {
  const fs::path dir = scan_file.parent_path();
  const std::string name = dir.filename().string();
  if (name == "radar" || name == "polar_oxford_form" || name == "Navtech_Polar") return dir.parent_path();
  if (name == "polar" && dir.parent_path().filename() == "radar" &&
      dir.parent_path().parent_path().filename() == "sensor_data")
    return dir.parent_path().parent_path().parent_path();
  return std::nullopt;
}
}  // namespace io_detail

}  // namespace radarslam
