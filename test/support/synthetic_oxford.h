#pragma once
// A small Oxford-layout dataset of random-noise scans (400 azimuths x 200 bins, 0.0438 m/bin,
// 4 Hz, 1 m apart along x, with ground truth) for tests that need real files but no content.
#include <mrpt/math/TPose2D.h>

#include <cstdint>
#include <filesystem>
#include <random>

#include "radarslam/io/oxford_writer.h"
#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::test {

inline void writeNoiseOxfordDataset(const std::filesystem::path& dir, int scans, unsigned seed) {
  OxfordWriter w(dir);
  std::mt19937 rng(seed);
  for (int i = 0; i < scans; ++i) {
    CObservationRadarScan scan;
    scan.resize(400, 200);
    scan.range_resolution_m = 0.0438;
    for (auto& p : scan.power) p = static_cast<std::uint8_t>(rng() % 80);
    for (std::uint32_t a = 0; a < 400; ++a)
      scan.azimuth_stamps_ns[a] = 1'600'000'000'000'000'000LL + i * 250'000'000LL + a * 625'000LL;
    scan.updateReferenceTime();
    w.writeScan(scan, mrpt::math::TPose2D(i * 1.0, 0, 0));
  }
  w.finish();
}

}  // namespace radarslam::test
