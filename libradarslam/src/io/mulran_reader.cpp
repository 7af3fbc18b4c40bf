// MulRan (Navtech CIR204-H): polar_oxford_form/<t_ns>.png (Oxford byte layout, ns stamps) or the
// plain transposed sensor_data/radar/polar/<t_ns>.png; scans are stamped at the END of the sweep
// (last azimuth); global_pose.csv ground truth (FORMATS.md section 2).
//
// Plain polar azimuth order: column j is the j-th azimuth in firing order (the image is the
// transpose of the Oxford layout, as written by MulRan's player from the per-ray data), so we
// transpose. CFEAR instead rotates the image 90 deg counter-clockwise, which also reverses the
// azimuth order (its row 0 is our last column) and so mirrors the scan; we do not copy that.
// Angles of the plain images are uniform, 2*pi*j/N (the encoder counts are not stored).
#include <algorithm>
#include <string>

#include "polar_png.h"
#include "radarslam/core/errors.h"
#include "radarslam/io/ground_truth.h"
#include "readers.h"

namespace radarslam::io_detail {

namespace {

StampNs medianInterval(const std::vector<IndexEntry>& index) {
  if (index.size() < 2) return kNominalSweepNs;
  std::vector<StampNs> d;
  for (std::size_t i = 1; i < index.size(); ++i) d.push_back(index[i].stamp - index[i - 1].stamp);
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

class MulRanReader : public FileSequenceReader {
 public:
  MulRanReader(const std::filesystem::path& root, DatasetKind kind, const ReaderOptions& o, OpenFlags flags)
      : FileSequenceReader(
            kind, root,
            listStampedFiles(kind == DatasetKind::MulRanOxfordForm ? root / "polar_oxford_form"
                                                                   : root / "sensor_data" / "radar" / "polar",
                             ".png")) {
    format_.range_resolution_m = o.range_resolution_m > 0 ? o.range_resolution_m : kMulRanResolution;
    format_.range_offset_m = o.range_offset_m.value_or(format_.range_resolution_m / 2);
    sweep_ns_ = medianInterval(index_);
    const auto gt = root / "global_pose.csv";
    if (flags.load_ground_truth && std::filesystem::exists(gt)) ground_truth_ = readMulRanGroundTruth(gt);
  }
  std::string sensorName() const override { return "Navtech CIR204-H"; }
  CObservationRadarScan::Ptr readScan(std::size_t i) const override {
    const auto& e = entry(i);
    if (kind_ == DatasetKind::MulRanPolar) {
      const cv::Mat img = readImage(i);
      // End-stamped sweep: the last azimuth is at the file's time.
      return decodeTransposed(
          img, e.file, format_.range_resolution_m, format_.range_offset_m,
          evenlySpacedStamps(static_cast<std::size_t>(img.cols), sweep_ns_, e.stamp, 1.0));
    }
    auto scan = decodeOxfordStyle(readImage(i), e.file, format_);
    const StampNs tol = kNsPerSec / 1000;
    if (e.stamp < scan->azimuth_stamps_ns.front() - tol || e.stamp > scan->azimuth_stamps_ns.back() + tol)
      throw InputError(e.file.string(), "file timestamp is outside the scan's azimuth timestamps");
    return scan;
  }

 private:
  OxfordStyleFormat format_;
  StampNs sweep_ns_ = kNominalSweepNs;
};

}  // namespace

std::unique_ptr<DatasetReader> openMulRan(const std::filesystem::path& root, DatasetKind kind,
                                          const ReaderOptions& o, OpenFlags f) {
  return std::make_unique<MulRanReader>(root, kind, o, f);
}

}  // namespace radarslam::io_detail
