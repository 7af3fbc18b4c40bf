// MulRan per-ray CSV scan, sensor_data/radar/ray/<t_ns>.csv (FORMATS.md 2.1): one line per
// azimuth, "t_ns, angle_deg, encoder_count, counter, bin_0 ... bin_{B-1}"; the file name is the
// last azimuth's time (MulRan stamps scans at the end of the sweep).
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>

#include "polar_png.h"
#include "radarslam/core/errors.h"
#include "readers.h"
#include "text_util.h"

namespace radarslam::io_detail {

CObservationRadarScan::Ptr readMulRanRayCsv(const std::filesystem::path& csv, const ReaderOptions& o) {
  auto in = openText(csv, "MulRan ray CSV");
  std::vector<std::vector<std::uint8_t>> rows;
  std::vector<StampNs> stamps;
  std::vector<double> angles;
  std::size_t bins = 0;
  forEachDataLine(in, csv, ',', 0, [&](const DataLine& d) {
    const std::string& where = d.where;
    const auto& f = d.fields;
    if (f.size() < 5)
      throw InputError(where, "malformed row: expected 't_ns,angle_deg,encoder,counter,bins...'");
    if (bins == 0) bins = f.size() - 4;
    if (f.size() - 4 != bins)
      throw InputError(where, "malformed row: " + std::to_string(f.size()) + " fields, previous rows had " +
                                  std::to_string(bins + 4));
    stamps.push_back(parseStamp(f[0], where, "timestamp"));
    const auto encoder = parseInt(f[2], where, "encoder count");
    if (encoder < 0 || encoder >= static_cast<std::int64_t>(kEncoderCountsPerTurn))
      throw InputError(where, "encoder count " + std::to_string(encoder) + " outside [0, 5600)");
    angles.push_back(static_cast<double>(encoder) / kEncoderCountsPerTurn * 2.0 * std::numbers::pi);
    if (stamps.size() > 1 && stamps.back() < stamps[stamps.size() - 2])
      throw InputError(where, "azimuth timestamp goes backwards");
    std::vector<std::uint8_t> row(bins);
    for (std::size_t b = 0; b < bins; ++b) {
      const auto v = parseInt(f[4 + b], where, "range bin");
      if (v < 0 || v > 255)
        throw InputError(where, "range bin value " + std::to_string(v) + " outside 0..255");
      row[b] = static_cast<std::uint8_t>(v);
    }
    rows.push_back(std::move(row));
  });
  if (rows.size() < 2) throw InputError(csv.string(), "fewer than 2 azimuth rows");
  // The file name, when it is a timestamp, is the last azimuth's time (1 ms tolerance).
  if (StampNs name_stamp = 0; parseStampByDigits(csv.stem().string(), name_stamp) &&
                              std::abs(name_stamp - stamps.back()) > kNsPerSec / 1000)
    throw InputError(csv.string(),
                     "file name " + csv.stem().string() + " is not the last azimuth's timestamp " +
                         std::to_string(stamps.back()) + " (MulRan stamps scans at the sweep end)");
  auto scan = CObservationRadarScan::Create();
  scan->resize(static_cast<std::uint32_t>(rows.size()), static_cast<std::uint32_t>(bins));
  scan->sensorLabel = "radar";
  scan->range_resolution_m = o.range_resolution_m > 0 ? o.range_resolution_m : kMulRanResolution;
  scan->range_offset_m = o.range_offset_m.value_or(scan->range_resolution_m / 2);
  for (std::size_t a = 0; a < rows.size(); ++a) std::memcpy(scan->row(a).data(), rows[a].data(), bins);
  scan->azimuth_stamps_ns = std::move(stamps);
  scan->azimuth_angles_rad = std::move(angles);
  scan->updateReferenceTime();
  return scan;
}

}  // namespace radarslam::io_detail
