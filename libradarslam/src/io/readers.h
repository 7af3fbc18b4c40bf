#pragma once
// Internal: the concrete dataset readers behind openDataset(). Each dataset lives in its own
// <name>_reader.cpp and is created by its factory below.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "png_file.h"
#include "radarslam/io/dataset.h"

namespace radarslam::io_detail {

struct IndexEntry {
  StampNs stamp = 0;  ///< the dataset's own stamp of the scan (file name or timestamp list)
  std::filesystem::path file;
};

/// Common part of the readers whose scans are one file each, indexed by a sorted stamp list.
class FileSequenceReader : public DatasetReader {
 public:
  FileSequenceReader(DatasetKind kind, std::filesystem::path root, std::vector<IndexEntry> index);
  DatasetKind kind() const override { return kind_; }
  const std::filesystem::path& root() const override { return root_; }
  std::size_t size() const override { return index_.size(); }
  StampNs indexStamp(std::size_t i) const override { return entry(i).stamp; }
  std::filesystem::path scanPath(std::size_t i) const override { return entry(i).file; }
  const Trajectory& groundTruth() const override { return ground_truth_; }
  /// Index of the scan stored in `file` (matched by file name), or nullopt.
  std::optional<std::size_t> findFile(const std::filesystem::path& file) const;

 protected:
  const IndexEntry& entry(std::size_t i) const;
  /// Decodes the image of scan i, checking that its size matches the sequence's first scan
  /// (the geometry is taken from the data; one sensor per sequence).
  cv::Mat readImage(std::size_t i) const;
  /// Interval between scan i and its neighbour (next, or previous for the last scan), or
  /// `fallback` for a one-scan sequence: the sweep duration of sensors without azimuth stamps.
  StampNs frameInterval(std::size_t i, StampNs fallback) const;

  DatasetKind kind_;
  std::filesystem::path root_;
  std::vector<IndexEntry> index_;
  Trajectory ground_truth_;
  std::optional<PngSize> expected_size_;  // of the first readable scan in the index
  std::filesystem::path expected_size_file_;
};

/// Lists `dir/*.<ext>` whose stems are UNIX timestamps (unit by digit count), sorted by time.
/// Throws InputError(dir, ...) if the directory is missing or holds no such file, or if a file
/// name is not a timestamp.
std::vector<IndexEntry> listStampedFiles(const std::filesystem::path& dir, const std::string& ext);

struct OpenFlags {
  bool load_ground_truth = true;
};

std::unique_ptr<DatasetReader> openOxford(const std::filesystem::path& root, const ReaderOptions& o,
                                          OpenFlags f);
std::unique_ptr<DatasetReader> openMulRan(const std::filesystem::path& root, DatasetKind kind,
                                          const ReaderOptions& o, OpenFlags f);
std::unique_ptr<DatasetReader> openBoreas(const std::filesystem::path& root, const ReaderOptions& o,
                                          OpenFlags f);
std::unique_ptr<DatasetReader> openRadiate(const std::filesystem::path& root, const ReaderOptions& o,
                                           OpenFlags f);
std::unique_ptr<DatasetReader> openRawlog(const std::filesystem::path& file);

/// Decodes a MulRan per-ray CSV scan (sensor_data/radar/ray/<t_ns>.csv).
CObservationRadarScan::Ptr readMulRanRayCsv(const std::filesystem::path& csv, const ReaderOptions& o);

/// Dataset root for a scan file by its folder names (radar/, polar_oxford_form/,
/// sensor_data/radar/polar/, Navtech_Polar/), or nullopt.
std::optional<std::filesystem::path> datasetRootOfScanFile(const std::filesystem::path& scan_file);

// Default geometry per sensor (FORMATS.md section 5).
constexpr double kOxfordResolution = 0.0432;      // CTS350-X, Oxford SDK
constexpr double kMulRanResolution = 0.05952;     // CIR204-H, ORORA
constexpr double kBoreasOldResolution = 0.0596;   // CIR204-H before the upgrade
constexpr double kBoreasNewResolution = 0.04381;  // after 1632182400 s, and RAS6
constexpr StampNs kBoreasResolutionUpgrade = 1632182400LL * kNsPerSec;
constexpr double kBoreasRangeOffset = -0.31;
constexpr std::uint32_t kRas6Bins = 6848;
constexpr double kRadiateResolution = 0.173611;   // RADIATE SDK config.yaml
constexpr StampNs kNominalSweepNs = 250'000'000;  // 4 Hz Navtech

}  // namespace radarslam::io_detail
