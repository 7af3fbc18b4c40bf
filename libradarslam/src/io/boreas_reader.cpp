// Boreas: radar/<t_us>.png in the Oxford byte layout, stamped at the MIDDLE azimuth; column 10 is
// unused (CIR204-H) or a chirp flag (RAS6: read into azimuth_chirp), so every azimuth counts as
// valid; range offset -0.31 m;
// applanix/radar_poses.csv ground truth (FORMATS.md section 3). Three geometries:
//   CIR204-H 3360 bins x 0.0596 m (scans before UNIX 1632182400 s), 3360 x 0.04381 m after,
//   RAS6 6848 bins x 0.04381 m (recognised by the image width).
#include <string>

#include "polar_png.h"
#include "radarslam/core/errors.h"
#include "radarslam/io/ground_truth.h"
#include "readers.h"

namespace radarslam::io_detail {

namespace {

class BoreasReader : public FileSequenceReader {
 public:
  BoreasReader(const std::filesystem::path& root, const ReaderOptions& o, OpenFlags flags)
      : FileSequenceReader(DatasetKind::Boreas, root, listStampedFiles(root / "radar", ".png")), options_(o) {
    const auto gt = root / "applanix" / "radar_poses.csv";
    if (flags.load_ground_truth && std::filesystem::exists(gt)) ground_truth_ = readBoreasGroundTruth(gt);
  }
  std::string sensorName() const override {
    if (expected_size_ && static_cast<std::uint32_t>(expected_size_->width - kOxfordMetaColumns) == kRas6Bins)
      return "Navtech RAS6";
    return "Navtech CIR204-H";
  }
  CObservationRadarScan::Ptr readScan(std::size_t i) const override {
    const auto& e = entry(i);
    const cv::Mat img = readImage(i);
    OxfordStyleFormat format;
    format.use_valid_column = false;
    const bool ras6 = img.cols - kOxfordMetaColumns == static_cast<int>(kRas6Bins);
    format.chirp_column = ras6;  // consecutive azimuths alternate up/down chirps (Boreas-RT)
    format.range_resolution_m = options_.range_resolution_m > 0                 ? options_.range_resolution_m
                                : (ras6 || e.stamp >= kBoreasResolutionUpgrade) ? kBoreasNewResolution
                                                                                : kBoreasOldResolution;
    format.range_offset_m = options_.range_offset_m.value_or(kBoreasRangeOffset);
    auto scan = decodeOxfordStyle(img, e.file, format);
    const StampNs tol = kNsPerSec / 1000;
    if (e.stamp < scan->azimuth_stamps_ns.front() - tol || e.stamp > scan->azimuth_stamps_ns.back() + tol)
      throw InputError(e.file.string(), "file timestamp is outside the scan's azimuth timestamps");
    return scan;
  }

 private:
  ReaderOptions options_;
};

}  // namespace

std::unique_ptr<DatasetReader> openBoreas(const std::filesystem::path& root, const ReaderOptions& o,
                                          OpenFlags f) {
  return std::make_unique<BoreasReader>(root, o, f);
}

}  // namespace radarslam::io_detail
