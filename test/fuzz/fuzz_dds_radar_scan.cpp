// Fuzz target: a live radar scan sample (radarslam/RadarScan, docs/dds.md "Radar scan input")
// through ScanStreamFilter (scanFromMessage + checkScanPlausible + the stamp order rule), as
// `radarslam localize MAP dds:` takes it. The bytes are decoded field by field into a RadarScanMsg
// (what Cyclone DDS hands over after deserialising any sample a publisher sends):
//   u32 num_azimuths, u32 num_bins, f64 range_resolution, f64 range_offset, i32 stamp sec,
//   u32 stamp nanosec, u8 frame_id length, u16 lengths of azimuth_stamps_ns / azimuth_angles /
//   azimuth_valid, u32 power length, then the arrays (each cut to what the input holds).
// Every accepted scan must be consistent, and a second, identical sample must be dropped.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "fuzz_common.h"
#include "radarslam/dds/scan_messages.h"
#include "radarslam/dds/scan_stream_filter.h"
#include "radarslam/obs/scan_checks.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radarslam;
  fuzz::ByteReader in(data, size);
  dds::RadarScanMsg m;
  m.num_azimuths = in.get<std::uint32_t>();
  m.num_bins = in.get<std::uint32_t>();
  m.range_resolution = in.get<double>();
  m.range_offset = in.get<double>();
  m.header.stamp.sec = in.get<std::int32_t>();
  m.header.stamp.nanosec = in.get<std::uint32_t>();
  const auto label = in.array<char>(in.get<std::uint8_t>());
  m.header.frame_id.assign(label.begin(), label.end());
  const auto n_stamps = in.get<std::uint16_t>(), n_angles = in.get<std::uint16_t>(),
             n_valid = in.get<std::uint16_t>();
  const auto n_power = in.get<std::uint32_t>();
  m.azimuth_stamps_ns = in.array<std::int64_t>(n_stamps);
  m.azimuth_angles = in.array<double>(n_angles);
  m.azimuth_valid = in.array<std::uint8_t>(n_valid);
  m.power = in.array<std::uint8_t>(n_power);

  dds::ScanStreamFilter filter("rt/fuzz");
  const auto scan = filter.accept(m);
  if (!scan) return 0;
  if (!checkScanPlausible(*scan).empty()) std::abort();  // accepted but implausible
  if (dds::scanMessage(*scan, m.header.frame_id).power != m.power) std::abort();
  if (filter.accept(m)) std::abort();  // the same stamp twice
  return 0;
}
