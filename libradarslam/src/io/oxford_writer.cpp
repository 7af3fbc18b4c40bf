#include "radarslam/io/oxford_writer.h"

#include <mrpt/poses/CPose2D.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "readers.h"

namespace radarslam {

namespace fs = std::filesystem;

namespace {
std::int64_t toMicros(StampNs t) { return t >= 0 ? t / kNsPerUs : -((-t + kNsPerUs - 1) / kNsPerUs); }

std::string secondsText(StampNs t) {  // exact "s.nnnnnnnnn" (no double rounding)
  char buf[48];
  std::snprintf(buf, sizeof buf, "%lld.%09lld", static_cast<long long>(t / kNsPerSec),
                static_cast<long long>(t % kNsPerSec));
  return buf;
}
}  // namespace

std::vector<unsigned char> encodeOxfordPng(const CObservationRadarScan& scan, int png_compression,
                                           int encoder_size) {
  const std::string problem = scan.checkConsistency();
  if (!problem.empty()) throw InputError("encodeOxfordPng", problem);
  const int rows = static_cast<int>(scan.num_azimuths), cols = 11 + static_cast<int>(scan.num_bins);
  const bool chirp_flag = scan.hasChirpDirections();
  cv::Mat img(rows, cols, CV_8UC1);
  for (int a = 0; a < rows; ++a) {
    std::uint8_t* p = img.ptr<std::uint8_t>(a);
    const std::int64_t us = toMicros(scan.azimuth_stamps_ns[static_cast<std::size_t>(a)]);
    for (int k = 0; k < 8; ++k)
      p[k] = static_cast<std::uint8_t>((static_cast<std::uint64_t>(us) >> (8 * k)) & 0xFF);
    double angle = std::fmod(scan.azimuth_angles_rad[static_cast<std::size_t>(a)], 2 * std::numbers::pi);
    if (angle < 0) angle += 2 * std::numbers::pi;
    const auto count =
        static_cast<std::uint16_t>(std::lround(angle / (2 * std::numbers::pi) * encoder_size) % encoder_size);
    p[8] = static_cast<std::uint8_t>(count & 0xFF);
    p[9] = static_cast<std::uint8_t>(count >> 8);
    if (chirp_flag)
      p[10] = scan.chirp(static_cast<std::size_t>(a)) > 0 ? 255 : 0;
    else
      p[10] = scan.azimuth_valid[static_cast<std::size_t>(a)] ? 255 : 0;
    const auto row = scan.row(static_cast<std::size_t>(a));
    std::memcpy(p + 11, row.data(), row.size());
  }
  std::vector<unsigned char> bytes;
  // Huffman-only: radar speckle has few repeats for LZ matching; this is faster and smaller.
  if (!cv::imencode(".png", img, bytes,
                    {cv::IMWRITE_PNG_COMPRESSION, png_compression, cv::IMWRITE_PNG_STRATEGY,
                     cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY}))
    throw InputError("encodeOxfordPng", "PNG encoding failed");
  return bytes;
}

OxfordWriter::OxfordWriter(fs::path root, int png_compression, int encoder_size)
    : root_(std::move(root)), compression_(png_compression), encoder_size_(encoder_size) {
  std::error_code ec;
  fs::create_directories(root_ / "radar", ec);
  if (!ec) fs::create_directories(root_ / "gt", ec);
  if (ec) throw InputError(root_.string(), "cannot create output directories: " + ec.message());
}

void OxfordWriter::writeScan(const CObservationRadarScan& scan, const mrpt::math::TPose2D& truth) {
  if (scan.azimuth_stamps_ns.empty()) throw InputError(root_.string(), "scan without azimuths");
  const std::int64_t name = toMicros(scan.azimuth_stamps_ns.front());
  if (!names_us_.empty() && name <= names_us_.back())
    throw InputError(root_.string(), "scan stamps must increase (" + std::to_string(name) + ")");
  if (names_us_.empty()) {
    resolution_m_ = scan.range_resolution_m, offset_m_ = scan.range_offset_m;
    chirp_flag_ = scan.hasChirpDirections();
  } else if (scan.range_resolution_m != resolution_m_ || scan.range_offset_m != offset_m_) {
    throw InputError(root_.string(), "all scans of a sequence must have the same range geometry");
  }
  const auto bytes = encodeOxfordPng(scan, compression_, encoder_size_);
  writeBytesAtomically(root_ / "radar" / (std::to_string(name) + ".png"), bytes);
  names_us_.push_back(name);
  truth_.push_back({scan.refStampNs(), truth});
}

void OxfordWriter::finish() {
  char line[256];
  if (!names_us_.empty() && (chirp_flag_ || std::abs(resolution_m_ - io_detail::kOxfordResolution) > 1e-12 ||
                             std::abs(offset_m_ - resolution_m_ / 2) > 1e-12)) {
    std::snprintf(line, sizeof line, "range_resolution_m %.10g\nrange_offset_m %.10g\n%s", resolution_m_,
                  offset_m_, chirp_flag_ ? "chirp_flag 1\n" : "");
    writeTextAtomically(root_ / "radar.geometry", line);
  }
  std::string stamps;
  for (const auto t : names_us_) stamps.append(std::to_string(t)).append(" 1\n");
  writeTextAtomically(root_ / "radar.timestamps", stamps);

  std::string csv =
      "source_timestamp,destination_timestamp,x,y,z,roll,pitch,yaw,source_radar_timestamp,"
      "destination_radar_timestamp\n";
  for (std::size_t k = 1; k < truth_.size(); ++k) {
    const mrpt::poses::CPose2D dst(truth_[k - 1].pose), src(truth_[k].pose);
    const mrpt::poses::CPose2D rel = src - dst;  // pose of the later scan in the earlier one
    std::snprintf(line, sizeof line, "%lld,%lld,%.9f,%.9f,0.000000,0.000000,0.000000,%.9f,%lld,%lld\n",
                  static_cast<long long>(toMicros(truth_[k].stamp)),
                  static_cast<long long>(toMicros(truth_[k - 1].stamp)), rel.x(), rel.y(), rel.phi(),
                  static_cast<long long>(names_us_[k]), static_cast<long long>(names_us_[k - 1]));
    csv += line;
  }
  writeTextAtomically(root_ / "gt" / "radar_odometry.csv", csv);

  std::string tum = "# radarslam simulator ground truth: radar pose at mid-sweep, t x y z qx qy qz qw\n";
  for (const auto& p : truth_) {
    std::snprintf(line, sizeof line, " %.6f %.6f 0 0 0 %.9f %.9f\n", p.pose.x, p.pose.y,
                  std::sin(p.pose.phi / 2), std::cos(p.pose.phi / 2));
    tum.append(secondsText(p.stamp)).append(line);
  }
  writeTextAtomically(root_ / "gt" / "poses.tum", tum);
}

}  // namespace radarslam
