// openDataset / readScanFile: dispatch to the reader of the detected layout.
#include <string>

#include "radarslam/core/errors.h"
#include "readers.h"

namespace radarslam {

namespace {
std::unique_ptr<DatasetReader> open(const std::filesystem::path& path, DatasetKind kind,
                                    const ReaderOptions& o, io_detail::OpenFlags flags) {
  switch (kind) {
    case DatasetKind::Oxford:
      return io_detail::openOxford(path, o, flags);
    case DatasetKind::MulRanOxfordForm:
    case DatasetKind::MulRanPolar:
      return io_detail::openMulRan(path, kind, o, flags);
    case DatasetKind::Boreas:
      return io_detail::openBoreas(path, o, flags);
    case DatasetKind::Radiate:
      return io_detail::openRadiate(path, o, flags);
    case DatasetKind::Rawlog:
      return io_detail::openRawlog(path);
  }
  throw InputError(path.string(), "unknown dataset kind");
}
}  // namespace

std::unique_ptr<DatasetReader> openDataset(const std::filesystem::path& path, const ReaderOptions& options) {
  return open(path, detectDatasetKind(path), options, {});
}

CObservationRadarScan::Ptr readScanFile(const std::filesystem::path& scan_file,
                                        const ReaderOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(scan_file, ec))
    throw InputError(scan_file.string(), "no such file (missing or unreadable)");
  if (scan_file.extension() == ".csv") return io_detail::readMulRanRayCsv(scan_file, options);
  if (scan_file.extension() != ".png")
    throw InputError(scan_file.string(),
                     "unknown scan file type: expected a polar .png or a MulRan ray .csv");
  const auto root = io_detail::datasetRootOfScanFile(scan_file);
  if (!root)
    throw InputError(scan_file.string(),
                     "cannot tell the dataset of this PNG: expected it inside radar/ "
                     "(Oxford, Boreas), polar_oxford_form/ or sensor_data/radar/polar/ "
                     "(MulRan), or Navtech_Polar/ (RADIATE)");
  io_detail::OpenFlags flags;
  flags.load_ground_truth = false;
  const auto reader = open(*root, detectDatasetKind(*root), options, flags);
  const auto* seq = dynamic_cast<const io_detail::FileSequenceReader*>(reader.get());
  const auto index = seq ? seq->findFile(scan_file) : std::nullopt;
  if (!index)
    throw InputError(scan_file.string(), "not listed in the index of its " + toString(reader->kind()) +
                                             " dataset at " + root->string());
  return reader->readScan(*index);
}

}  // namespace radarslam
