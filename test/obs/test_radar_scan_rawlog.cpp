#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include <random>

#include "radarslam/obs/CObservationRadarScan.h"
#include "radarslam/obs/registration.h"
#include "temp_dir.h"

using namespace radarslam;

namespace {
CObservationRadarScan::Ptr makeScan(unsigned seed, std::uint32_t azimuths, std::uint32_t bins) {
  auto s = CObservationRadarScan::Create();
  s->resize(azimuths, bins);
  s->sensorLabel = "navtech";
  s->range_resolution_m = 0.0432;
  s->range_offset_m = 0.0216;
  std::mt19937 rng(seed);
  for (auto& p : s->power) p = static_cast<std::uint8_t>(rng());
  for (std::uint32_t i = 0; i < azimuths; ++i) {
    s->azimuth_stamps_ns[i] = 1547131046353776000LL + i * 625000LL + seed;
    s->azimuth_valid[i] = (i % 7) ? 1 : 0;
  }
  s->sensorPose = mrpt::poses::CPose3D(-0.71813, 0.12, -0.54479, 0, 0.05, 0);
  s->updateReferenceTime();
  return s;
}
}  // namespace

TEST(CObservationRadarScan, ReferenceTimeIsMidSweep) {
  auto s = makeScan(0, 400, 10);
  EXPECT_EQ(s->refStampNs(), 1547131046353776000LL + 399 * 625000LL / 2);
  EXPECT_EQ(s->checkConsistency(), "");
  s->power.pop_back();
  EXPECT_NE(s->checkConsistency(), "");
}

TEST(CObservationRadarScan, RawlogRoundTripPreservesEveryByte) {
  registerRadarslamClasses();
  test::TempDir dir;
  const auto file = (dir / "scans.rawlog").string();
  std::vector<CObservationRadarScan::Ptr> scans;
  mrpt::obs::CRawlog out;
  for (unsigned i = 0; i < 5; ++i) {
    scans.push_back(makeScan(i, 400, 3768 - i));
    out.insert(scans.back());
  }
  ASSERT_TRUE(out.saveToRawLogFile(file));

  mrpt::obs::CRawlog in;
  ASSERT_TRUE(in.loadFromRawLogFile(file));
  ASSERT_EQ(in.size(), scans.size());  // 0 here means the class was not registered
  for (std::size_t i = 0; i < scans.size(); ++i) {
    auto got = in.getAsObservation(i);
    auto r = std::dynamic_pointer_cast<CObservationRadarScan>(got);
    ASSERT_TRUE(r) << "entry " << i << " is not a radar scan";
    const auto& e = *scans[i];
    EXPECT_EQ(r->sensorLabel, e.sensorLabel);
    EXPECT_EQ(r->timestamp, e.timestamp);
    EXPECT_EQ(r->num_bins, e.num_bins);
    EXPECT_EQ(r->range_resolution_m, e.range_resolution_m);
    EXPECT_EQ(r->range_offset_m, e.range_offset_m);
    EXPECT_EQ(r->power, e.power);
    EXPECT_EQ(r->azimuth_stamps_ns, e.azimuth_stamps_ns);
    EXPECT_EQ(r->azimuth_angles_rad, e.azimuth_angles_rad);
    EXPECT_EQ(r->azimuth_valid, e.azimuth_valid);
    EXPECT_EQ(r->sensorPose, e.sensorPose);
  }
}
