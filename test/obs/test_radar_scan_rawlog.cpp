#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
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
    if (seed % 2) s->azimuth_chirp[i] = (i % 2) ? 1 : -1;  // odd seeds: alternating chirp (RAS6)
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
    EXPECT_EQ(r->azimuth_chirp, e.azimuth_chirp);
    EXPECT_EQ(r->hasChirpDirections(), i % 2 == 1);
    EXPECT_EQ(r->sensorPose, e.sensorPose);
  }
}

TEST(CObservationRadarScan, ChirpDirectionsAreChecked) {
  auto s = makeScan(1, 40, 10);
  EXPECT_TRUE(s->hasChirpDirections());
  EXPECT_EQ(s->chirp(1), 1);
  EXPECT_EQ(s->chirp(2), -1);
  EXPECT_EQ(s->chirp(1000), 0);  // outside: unknown
  s->azimuth_chirp.clear();      // empty = unknown everywhere, still consistent
  EXPECT_EQ(s->checkConsistency(), "");
  EXPECT_FALSE(s->hasChirpDirections());
  s->azimuth_chirp.assign(39, 1);
  EXPECT_NE(s->checkConsistency().find("azimuth_chirp"), std::string::npos);
  s->azimuth_chirp.assign(40, 2);
  EXPECT_NE(s->checkConsistency().find("azimuth_chirp"), std::string::npos);
}

// Rawlogs written before the chirp directions existed (serialization version 0) still load, with
// the chirp unknown. The version-0 bytes are made from a version-1 object without chirp
// directions: version byte 1 -> 0, and the trailing "no chirp" byte removed.
TEST(CObservationRadarScan, VersionZeroArchivesStillLoad) {
  registerRadarslamClasses();
  auto s = makeScan(2, 30, 17);
  ASSERT_FALSE(s->hasChirpDirections());
  mrpt::io::CMemoryStream mem;
  mrpt::serialization::archiveFrom(mem).WriteObject(s.get());
  const auto* p = static_cast<const std::uint8_t*>(mem.getRawBufferData());
  std::vector<std::uint8_t> bytes(p, p + mem.getTotalBytesCount());
  const std::string name = "CObservationRadarScan";
  const auto at = std::search(bytes.begin(), bytes.end(), name.begin(), name.end());
  ASSERT_NE(at, bytes.end());
  const auto version = at + static_cast<std::ptrdiff_t>(name.size());
  ASSERT_EQ(*version, 1) << "version byte expected right after the class name";
  *version = 0;
  ASSERT_GE(bytes.size(), 2u);
  ASSERT_EQ(bytes[bytes.size() - 2], 0) << "version 1 without chirps ends with a 0 flag byte";
  bytes.erase(bytes.end() - 2);  // keep MRPT's end-of-object marker

  mrpt::io::CMemoryStream in;
  in.assignMemoryNotOwn(bytes.data(), bytes.size());
  auto obj = mrpt::serialization::archiveFrom(in).ReadObject();
  auto r = std::dynamic_pointer_cast<CObservationRadarScan>(obj);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->power, s->power);
  EXPECT_EQ(r->azimuth_valid, s->azimuth_valid);
  EXPECT_EQ(r->azimuth_chirp, std::vector<std::int8_t>(30, 0));
  EXPECT_EQ(r->checkConsistency(), "");
}
