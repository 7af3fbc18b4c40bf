#include "polar_png.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include "radarslam/core/errors.h"

namespace radarslam::io_detail {

namespace {

// Sensor timestamps are UNIX us (16 digits) or ns (19 digits) in the years 1973-2286.
bool azimuthStampToNs(std::int64_t v, StampNs& out) {
  if (v >= 100'000'000'000'000'000LL)
    out = v;  // ns
  else if (v >= 100'000'000'000'000LL && v < 10'000'000'000'000'000LL)
    out = v * kNsPerUs;  // us
  else
    return false;
  return true;
}

std::string rowWhere(int row) { return "azimuth row " + std::to_string(row) + ": "; }

}  // namespace

CObservationRadarScan::Ptr decodeOxfordStyle(const cv::Mat& img, const std::filesystem::path& file,
                                             const OxfordStyleFormat& format) {
  if (img.cols <= kOxfordMetaColumns || img.rows < 2)
    throw InputError(file.string(), "image is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                                        " (WxH); an Oxford-style polar scan needs >= 2 rows (azimuths) and " +
                                        std::to_string(kOxfordMetaColumns) +
                                        " metadata columns + range bins");
  auto scan = CObservationRadarScan::Create();
  scan->resize(static_cast<std::uint32_t>(img.rows),
               static_cast<std::uint32_t>(img.cols - kOxfordMetaColumns));
  scan->sensorLabel = "radar";
  scan->range_resolution_m = format.range_resolution_m;
  scan->range_offset_m = format.range_offset_m;
  for (int r = 0; r < img.rows; ++r) {
    const std::uint8_t* p = img.ptr<std::uint8_t>(r);
    std::int64_t raw = 0;
    for (int b = 7; b >= 0; --b) raw = (raw << 8) | p[b];  // little-endian
    const std::uint16_t encoder = static_cast<std::uint16_t>(p[8] | (p[9] << 8));
    StampNs t = 0;
    if (!azimuthStampToNs(raw, t))
      throw InputError(file.string(), rowWhere(r) + "timestamp " + std::to_string(raw) +
                                          " is not a UNIX time in us or ns (wrong layout?)");
    if (encoder >= kEncoderCountsPerTurn)
      throw InputError(file.string(), rowWhere(r) + "encoder count " + std::to_string(encoder) + " >= 5600");
    if (r > 0 && t < scan->azimuth_stamps_ns[r - 1])
      throw InputError(file.string(), rowWhere(r) + "timestamp goes backwards");
    scan->azimuth_stamps_ns[r] = t;
    scan->azimuth_angles_rad[r] = encoder / kEncoderCountsPerTurn * 2.0 * std::numbers::pi;
    scan->azimuth_valid[r] = format.use_valid_column && !format.chirp_column ? (p[10] == 255 ? 1 : 0) : 1;
    scan->azimuth_chirp[r] = format.chirp_column ? (p[10] == 255 ? 1 : -1) : 0;
    std::memcpy(scan->row(r).data(), p + kOxfordMetaColumns, scan->num_bins);
  }
  // A flag column that never changes is not an alternating chirp (e.g. a RAS6 scan recorded before
  // pyboreas' radar_chirp_type_upgrade_time): single chirp, direction unknown.
  if (format.chirp_column && !scan->azimuth_chirp.empty() &&
      std::all_of(scan->azimuth_chirp.begin(), scan->azimuth_chirp.end(),
                  [&](std::int8_t c) { return c == scan->azimuth_chirp.front(); }))
    std::fill(scan->azimuth_chirp.begin(), scan->azimuth_chirp.end(), std::int8_t{0});
  if (scan->azimuth_stamps_ns.back() - scan->azimuth_stamps_ns.front() > 10 * kNsPerSec)
    throw InputError(file.string(), "sweep lasts more than 10 s (corrupt azimuth timestamps?)");
  scan->updateReferenceTime();
  return scan;
}

CObservationRadarScan::Ptr decodeTransposed(const cv::Mat& img, const std::filesystem::path& file,
                                            double range_resolution_m, double range_offset_m,
                                            const std::vector<StampNs>& azimuth_stamps) {
  if (img.rows < 1 || img.cols < 2)
    throw InputError(file.string(),
                     "image is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                         " (WxH); a transposed polar scan needs rows = range bins, >= 2 columns (azimuths)");
  if (azimuth_stamps.size() != static_cast<std::size_t>(img.cols))
    throw InputError(file.string(), "internal: " + std::to_string(azimuth_stamps.size()) + " stamps for " +
                                        std::to_string(img.cols) + " azimuths");
  auto scan = CObservationRadarScan::Create();
  scan->resize(static_cast<std::uint32_t>(img.cols), static_cast<std::uint32_t>(img.rows));  // uniform angles
  scan->sensorLabel = "radar";
  scan->range_resolution_m = range_resolution_m;
  scan->range_offset_m = range_offset_m;
  cv::Mat rows_are_azimuths = img.t();
  for (int a = 0; a < rows_are_azimuths.rows; ++a)
    std::memcpy(scan->row(a).data(), rows_are_azimuths.ptr<std::uint8_t>(a), scan->num_bins);
  scan->azimuth_stamps_ns = azimuth_stamps;
  scan->updateReferenceTime();
  return scan;
}

std::vector<StampNs> evenlySpacedStamps(std::size_t n, StampNs sweep_ns, StampNs anchor_stamp,
                                        double anchor) {
  std::vector<StampNs> out(n);
  if (n == 0) return out;
  const double step = static_cast<double>(sweep_ns) / static_cast<double>(n);
  const double anchor_index = anchor * static_cast<double>(n - 1);
  for (std::size_t j = 0; j < n; ++j)
    out[j] = anchor_stamp + std::llround((static_cast<double>(j) - anchor_index) * step);
  return out;
}

}  // namespace radarslam::io_detail
