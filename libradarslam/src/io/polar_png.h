#pragma once
// Decoding of the polar PNG layouts shared by several datasets (FORMATS.md sections 1-4).
//
// Oxford-style (Oxford, MulRan polar_oxford_form, Boreas): one row per azimuth; bytes 0-7 of a
// row are the azimuth's int64 little-endian UNIX timestamp (unit from its digit count: us for
// Oxford/Boreas, ns for MulRan), bytes 8-9 the uint16 LE encoder count (angle = count / 5600 * 2pi),
// byte 10 the valid flag (255 = genuine reading; Boreas: unused; RAS6 / Boreas-RT: the chirp
// flag, 255 = up-chirp, 0 = down-chirp), then one byte per range bin.
//
// Transposed (MulRan sensor_data/radar/polar, RADIATE Navtech_Polar): rows = range bins,
// columns = azimuths, no metadata; stamps and angles are supplied by the caller.
#include <filesystem>
#include <opencv2/core/mat.hpp>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::io_detail {

constexpr int kOxfordMetaColumns = 11;
constexpr double kEncoderCountsPerTurn = 5600.0;

struct OxfordStyleFormat {
  double range_resolution_m = 0.0;
  double range_offset_m = 0.0;
  /// false for Boreas, whose column 10 is unused / a chirp flag: every azimuth is valid.
  bool use_valid_column = true;
  /// true for RAS6 (and simulated alternating-chirp sequences): column 10 is the chirp flag,
  /// 255 -> azimuth_chirp +1 (up), anything else -> -1 (down). Implies use_valid_column = false.
  /// Which flag value is the up-chirp is our assumption (pyboreas documents only "chirp flag");
  /// a sensor with the opposite convention is handled by the sign of its Doppler beta. A column
  /// that is the same on every row is no alternation: azimuth_chirp stays 0 (single / unknown).
  bool chirp_column = false;
};

/// Decodes an Oxford-style polar image. Throws InputError(file, ...) if the image is too narrow,
/// or if the metadata is implausible (encoder count >= 5600, timestamps not a UNIX time or going
/// backwards, a sweep longer than 10 s).
CObservationRadarScan::Ptr decodeOxfordStyle(const cv::Mat& img, const std::filesystem::path& file,
                                             const OxfordStyleFormat& format);

/// Copies a transposed polar image (rows = bins, cols = azimuths) into a scan with uniform
/// angles 2*pi*j/N for column j and the given per-azimuth stamps (one per column).
CObservationRadarScan::Ptr decodeTransposed(const cv::Mat& img, const std::filesystem::path& file,
                                            double range_resolution_m, double range_offset_m,
                                            const std::vector<StampNs>& azimuth_stamps);

/// Per-azimuth stamps for a sweep without recorded azimuth times: N azimuths evenly spread over
/// `sweep_ns`, placed so that the azimuth at fraction `anchor` of the sweep (0 = first azimuth,
/// 0.5 = middle, 1 = last) is at `anchor_stamp`.
std::vector<StampNs> evenlySpacedStamps(std::size_t n, StampNs sweep_ns, StampNs anchor_stamp, double anchor);

}  // namespace radarslam::io_detail
