// Oxford Radar RobotCar: radar/<t_us>.png (stamp = first azimuth), radar.timestamps,
// gt/radar_odometry.csv (FORMATS.md section 1).
#include <cmath>
#include <cstdlib>
#include <string>

#include "polar_png.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/io/ground_truth.h"
#include "readers.h"
#include "text_util.h"

namespace radarslam::io_detail {

namespace {

// radar.timestamps: "<t_us> <flag>" per line, increasing. A line repeating the previous stamp (a
// duplicated scan) is kept: ScanIterator skips the duplicate with a warning and counts it.
std::vector<IndexEntry> readRadarTimestamps(const std::filesystem::path& root) {
  const auto file = root / "radar.timestamps";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(file.string(),
                     "missing radar.timestamps (Oxford layout: radar/*.png + radar.timestamps)");
  auto in = openText(file, "radar.timestamps");
  std::vector<IndexEntry> index;
  forEachDataLine(in, file, ' ', 0, [&](const DataLine& d) {
    const std::string& where = d.where;
    const auto& fields = d.fields;
    if (fields.empty() || fields.size() > 2)
      throw InputError(where, "malformed line: expected '<timestamp_us> <flag>'");
    IndexEntry e;
    e.stamp = parseMicroseconds(fields[0], where, "timestamp");
    e.file = root / "radar" / (std::string(fields[0]) + ".png");
    if (!index.empty() && e.stamp < index.back().stamp)
      throw InputError(where, "timestamps are not increasing (" + std::string(fields[0]) + " after " +
                                  std::to_string(index.back().stamp / kNsPerUs) + ")");
    index.push_back(std::move(e));
  });
  if (index.empty()) throw InputError(file.string(), "no timestamps");
  return index;
}

/// radar.geometry of a simulated sequence whose range geometry is not Oxford's (see
/// io/oxford_writer.h): "range_resolution_m <m>" and "range_offset_m <m>" lines, and optionally
/// "chirp_flag 1" (byte 10 of each row is the chirp flag of an alternating-chirp sensor).
void readGeometryFile(const std::filesystem::path& file, OxfordStyleFormat& format) {
  auto in = openText(file, "range geometry");
  std::string text;
  bool res = false, off = false;
  for (std::size_t line_no = 1; std::getline(in, text); ++line_no) {
    const auto line = trim(text);
    if (line.empty()) continue;
    const auto fields = split(line, ' ');
    const std::string where = lineWhere(file, line_no);
    if (fields.size() != 2) throw InputError(where, "expected '<key> <value>'");
    const double v = parseDouble(fields[1], where, "value");
    if (fields[0] == "range_resolution_m" && v > 0 && v <= 10)
      format.range_resolution_m = v, res = true;
    else if (fields[0] == "range_offset_m" && std::abs(v) <= 100)
      format.range_offset_m = v, off = true;
    else if (fields[0] == "chirp_flag" && (v == 0 || v == 1))
      format.chirp_column = v == 1;
    else
      throw InputError(where,
                       "unknown key or value out of range (range_resolution_m in (0, 10], "
                       "range_offset_m in [-100, 100], chirp_flag 0 or 1)");
  }
  if (!res || !off) throw InputError(file.string(), "needs range_resolution_m and range_offset_m");
}

class OxfordReader : public FileSequenceReader {
 public:
  OxfordReader(const std::filesystem::path& root, const ReaderOptions& o, OpenFlags flags)
      : FileSequenceReader(DatasetKind::Oxford, root, readRadarTimestamps(root)) {
    format_.range_resolution_m = o.range_resolution_m > 0 ? o.range_resolution_m : kOxfordResolution;
    // The SDK and yeti put bin k at (k + 0.5) * resolution: the offset is half a bin.
    format_.range_offset_m = o.range_offset_m.value_or(format_.range_resolution_m / 2);
    // A simulated sequence of another sensor's geometry says so (explicit options still win).
    if (const auto geo = root / "radar.geometry"; std::filesystem::exists(geo)) {
      OxfordStyleFormat f = format_;
      readGeometryFile(geo, f);
      format_.chirp_column = f.chirp_column;
      if (o.range_resolution_m <= 0) {
        format_.range_resolution_m = f.range_resolution_m;
        format_.range_offset_m = o.range_offset_m.value_or(f.range_offset_m);
      }
    }
    const auto gt = root / "gt" / "radar_odometry.csv";
    if (flags.load_ground_truth && std::filesystem::exists(gt)) ground_truth_ = readOxfordGroundTruth(gt);
  }
  std::string sensorName() const override { return "Navtech CTS350-X"; }
  CObservationRadarScan::Ptr readScan(std::size_t i) const override {
    auto scan = decodeOxfordStyle(readImage(i), entry(i).file, format_);
    // Oxford names a scan after its first azimuth (all real scans match exactly; 1 ms slack).
    if (std::abs(scan->azimuth_stamps_ns.front() - entry(i).stamp) > kNsPerSec / 1000)
      throw InputError(entry(i).file.string(),
                       "first azimuth timestamp " +
                           std::to_string(scan->azimuth_stamps_ns.front() / kNsPerUs) +
                           " differs from the file's timestamp (Oxford stamps scans at the "
                           "first azimuth)");
    return scan;
  }

 private:
  OxfordStyleFormat format_;
};

}  // namespace

std::unique_ptr<DatasetReader> openOxford(const std::filesystem::path& root, const ReaderOptions& o,
                                          OpenFlags f) {
  return std::make_unique<OxfordReader>(root, o, f);
}

}  // namespace radarslam::io_detail
