// Dataset kind from the directory layout (FORMATS.md section 5).
#include <string>

#include "png_file.h"
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

// A Boreas sequence downloaded radar-only (pyboreas fetches sensors separately; ground truth is
// optional): radar/ holds <t_us>.png scans whose width is 11 metadata columns + the bins of a
// Boreas geometry (CIR204-H 3360, RAS6 6848). The first scan (by name) decides.
bool looksLikeBoreasRadarOnly(const fs::path& radar_dir) {
  std::error_code ec;
  fs::path first;
  for (fs::directory_iterator it(radar_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() != ".png") continue;
    if (first.empty() || p.filename() < first.filename()) first = p;
  }
  if (first.empty()) return false;
  const std::string stem = first.stem().string();
  if (stem.size() != 16 || stem.find_first_not_of("0123456789") != std::string::npos) return false;
  try {
    const io_detail::PngSize size = io_detail::readPngSize(first);
    return size.width == 3360 + 11 || size.width == 6848 + 11;
  } catch (const InputError&) {
    return false;  // not a readable PNG: not recognised here (the readers report bad scans)
  }
}

const char* kExpected =
    "expected radar/ + radar.timestamps (Oxford), polar_oxford_form/ or sensor_data/radar/polar/ (MulRan), "
    "radar/ + applanix/ or radar/ of Boreas scans alone (Boreas), Navtech_Polar/ (+ Navtech_Polar.txt) "
    "(RADIATE), or a .rawlog file";
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
  // Navtech_Polar.txt (frame times) is optional: without it the reader times frames by number.
  if (isDir(path / "Navtech_Polar")) return DatasetKind::Radiate;
  if (isDir(path / "radar")) {
    if (looksLikeBoreasRadarOnly(path / "radar")) return DatasetKind::Boreas;
    throw InputError(
        (path / "radar.timestamps").string(),
        "missing radar.timestamps: radar/ needs radar.timestamps (Oxford), applanix/ (Boreas), or "
        "Boreas scans (<16-digit microsecond stamp>.png, 3360 or 6848 bins + 11 columns)");
  }
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
