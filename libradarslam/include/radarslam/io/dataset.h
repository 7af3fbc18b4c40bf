#pragma once
// Reading radar datasets. One entry point, openDataset(), detects the layout of a directory (or a
// .rawlog file) and returns a streaming reader: scans are decoded one at a time on request, never
// the whole sequence in memory. Geometry comes from the data (and optional overrides), never from
// a hard-coded Oxford size. Ground truth, when the dataset has it, is converted to radarslam's one
// convention: the radar's absolute SE(2) pose at each stamp (see core/trajectory.h), which is
// interpolated to a scan's reference time (CObservationRadarScan::refStampNs()).
//
// Errors: every problem with the data is an InputError whose where() is the offending file.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "radarslam/core/trajectory.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

namespace io_detail {
class ScanPrefetcher;
}

enum class DatasetKind { Oxford, MulRanOxfordForm, MulRanPolar, Boreas, Radiate, Rawlog };

std::string toString(DatasetKind kind);

/// The dataset kind of a directory (or .rawlog file) from its layout alone, without reading
/// scans. Throws InputError(path, ...) for a missing/empty path or an unknown layout.
DatasetKind detectDatasetKind(const std::filesystem::path& path);

struct ReaderOptions {
  /// Overrides of the sensor geometry where a format does not carry it (0 = use the default
  /// for the detected dataset/sensor).
  double range_resolution_m = 0.0;
  std::optional<double> range_offset_m;
};

class DatasetReader {
 public:
  virtual ~DatasetReader() = default;

  virtual DatasetKind kind() const = 0;
  /// The directory (or .rawlog file) this reader was opened on.
  virtual const std::filesystem::path& root() const = 0;
  /// Human-readable sensor name, e.g. "Navtech CTS350-X".
  virtual std::string sensorName() const = 0;

  /// Number of scans in the sequence index.
  virtual std::size_t size() const = 0;
  /// Stamp of scan i from the index (file name or timestamp list) without decoding the scan.
  /// This is the dataset's own stamp (Oxford: first azimuth; MulRan: last; Boreas: middle).
  virtual StampNs indexStamp(std::size_t i) const = 0;
  /// Decodes scan i (0-based, in time order). Throws InputError(file, problem) for a bad scan.
  virtual CObservationRadarScan::Ptr readScan(std::size_t i) const = 0;
  /// Path of the file holding scan i (for messages); the .rawlog itself for rawlogs.
  virtual std::filesystem::path scanPath(std::size_t i) const = 0;

  /// Optional parts of the layout that are absent other than the ground truth, each as
  /// "<file> missing: <what that disables>" (for `radarslam info`); empty when complete.
  virtual std::vector<std::string> missingParts() const { return {}; }

  /// Ground truth as absolute radar SE(2) poses; empty if the dataset has none.
  virtual const Trajectory& groundTruth() const = 0;
  bool hasGroundTruth() const { return !groundTruth().empty(); }
  /// Ground-truth pose at `t` (interpolated), nullopt outside the ground truth's span.
  std::optional<mrpt::math::TPose2D> groundTruthAt(StampNs t) const {
    return interpolatePose(groundTruth(), t);
  }
};

/// Detects the dataset kind from the directory layout (or a .rawlog file) and opens it.
/// Throws InputError(path, "unknown dataset layout: ...") naming what was expected.
std::unique_ptr<DatasetReader> openDataset(const std::filesystem::path& path,
                                           const ReaderOptions& options = {});

/// Decodes one scan file (an Oxford/Boreas/MulRan/RADIATE polar PNG, or a MulRan ray CSV) on
/// its own, detecting the format from the file and the dataset directory around it.
CObservationRadarScan::Ptr readScanFile(const std::filesystem::path& scan_file,
                                        const ReaderOptions& options = {});

/// What a ScanIterator skipped or flagged so far (for the commands' final summaries).
struct ScanIteratorStats {
  std::size_t skipped_unreadable = 0;  ///< bad scans skipped with skip_bad_scans
  std::size_t skipped_duplicate = 0;   ///< same reference time as the previous scan: always skipped
  std::size_t blank = 0;               ///< returned scans without any return (all-zero power), e.g. snow
  std::size_t time_gaps = 0;           ///< intervals > 1.5x the scan period (dropped scans, time jumps)
  StampNs largest_gap_ns = 0;          ///< largest interval between returned scans
  StampNs scan_period_ns = 0;          ///< median interval of the dataset's index (0: unknown)
};

/// Iterates a dataset in time order. Every scan is checked (decodes, consistent geometry, its
/// reference time later than the previous scan's). With skip_bad_scans a bad scan is logged as a
/// warning and skipped; without it the InputError naming the file propagates. A scan with the
/// same reference time as the previous one (a duplicated index entry) is always skipped with a
/// warning; an earlier one is a bad scan. Blank scans and time gaps are passed on, but counted
/// (stats()) and logged.
///
/// prefetch > 0: a background thread decodes up to that many scans ahead, so decoding overlaps
/// the caller's work on the previous scan. The scans, their order, the warnings and the errors
/// are the same as without it (a scan past a fatal error may have been decoded, never returned).
class ScanIterator {
 public:
  ScanIterator(const DatasetReader& reader, bool skip_bad_scans, std::size_t first = 0,
               std::size_t end = static_cast<std::size_t>(-1), std::size_t prefetch = 0);
  ~ScanIterator();
  ScanIterator(const ScanIterator&) = delete;
  ScanIterator& operator=(const ScanIterator&) = delete;
  /// The next good scan, or nullptr at the end.
  CObservationRadarScan::Ptr next();
  /// Dataset index of the scan last returned by next().
  std::size_t index() const { return last_; }
  std::size_t skipped() const { return skipped_; }     ///< unreadable + duplicate scans skipped
  std::size_t total() const { return end_ - first_; }  ///< scans this iterator will visit
  const ScanIteratorStats& stats() const { return stats_; }

 private:
  const DatasetReader& reader_;
  bool skip_;
  std::size_t first_, end_, pos_, last_ = 0, skipped_ = 0;
  StampNs last_stamp_ = 0;
  bool have_last_stamp_ = false;
  ScanIteratorStats stats_;
  std::unique_ptr<io_detail::ScanPrefetcher> prefetcher_;
};

}  // namespace radarslam
