// .rawlog round trip (Oxford tiny -> rawlog -> read back, every byte equal), random access,
// truncated files, and time order checks through ScanIterator.
#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/rawlog_writer.h"
#include "radarslam/obs/registration.h"
#include "shared_data.h"
#include "temp_dir.h"

using namespace radarslam;

namespace {
void expectSameScan(const CObservationRadarScan& a, const CObservationRadarScan& b) {
  EXPECT_EQ(a.num_azimuths, b.num_azimuths);
  EXPECT_EQ(a.num_bins, b.num_bins);
  EXPECT_EQ(a.range_resolution_m, b.range_resolution_m);
  EXPECT_EQ(a.range_offset_m, b.range_offset_m);
  EXPECT_EQ(a.timestamp, b.timestamp);
  EXPECT_EQ(a.sensorLabel, b.sensorLabel);
  EXPECT_TRUE(a.power == b.power);
  EXPECT_EQ(a.azimuth_stamps_ns, b.azimuth_stamps_ns);
  EXPECT_EQ(a.azimuth_angles_rad, b.azimuth_angles_rad);
  EXPECT_EQ(a.azimuth_valid, b.azimuth_valid);
}

std::unique_ptr<DatasetReader> openTiny() {
  return openDataset(test::realDataDir() / "oxford_radar_robotcar_tiny");
}
}  // namespace

TEST(Rawlog, OxfordRoundTripKeepsEveryByte) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  test::TempDir tmp;
  const auto src = openTiny();
  const auto file = tmp / "tiny.rawlog";
  {
    RawlogWriter w(file);
    ScanIterator it(*src, false);
    while (auto s = it.next()) w.write(*s);
    w.close();
    EXPECT_EQ(w.count(), 11u);
  }
  const auto back = openDataset(file);
  EXPECT_EQ(back->kind(), DatasetKind::Rawlog);
  ASSERT_EQ(back->size(), 11u);
  for (std::size_t i = 0; i < 11; ++i) {
    SCOPED_TRACE(i);
    const auto a = src->readScan(i);
    EXPECT_EQ(back->indexStamp(i), a->refStampNs());
    expectSameScan(*back->readScan(i), *a);
  }
  // Random access: backwards (re-reads from the start) and repeated requests.
  expectSameScan(*back->readScan(3), *src->readScan(3));
  expectSameScan(*back->readScan(3), *src->readScan(3));
  expectSameScan(*back->readScan(9), *src->readScan(9));
  // MRPT's own CRawlog reads the file too (after class registration).
  registerRadarslamClasses();
  mrpt::obs::CRawlog rawlog;
  ASSERT_TRUE(rawlog.loadFromRawLogFile(file.string()));
  EXPECT_EQ(rawlog.size(), 11u);
}

TEST(Rawlog, TruncatedRawlogIsAnError) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  test::TempDir tmp;
  const auto src = openTiny();
  const auto file = tmp / "t.rawlog";
  {
    RawlogWriter w(file);
    for (std::size_t i = 0; i < 3; ++i) w.write(*src->readScan(i));
  }
  std::filesystem::resize_file(file, std::filesystem::file_size(file) * 2 / 3);
  test::expectInputError([&] { openDataset(file); }, "t.rawlog", "truncated rawlog");
  test::writeText(tmp / "empty.rawlog", "");
  test::expectInputError([&] { openDataset(tmp / "empty.rawlog"); }, "empty.rawlog", "no radar scans");
}

TEST(Rawlog, ScansOutOfTimeOrderAreRejectedByTheIterator) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  test::TempDir tmp;
  const auto src = openTiny();
  const auto file = tmp / "o.rawlog";
  {
    RawlogWriter w(file);
    for (std::size_t i : {0, 1, 3, 2, 4}) w.write(*src->readScan(i));
  }
  const auto reader = openDataset(file);
  ScanIterator strict(*reader, false);
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(strict.next());
  test::expectInputError([&] { strict.next(); }, "o.rawlog", "is not after the previous scan");
  ScanIterator lenient(*reader, true);
  std::vector<std::size_t> seen;
  while (lenient.next()) seen.push_back(lenient.index());
  EXPECT_EQ(seen, (std::vector<std::size_t>{0, 1, 2, 4}));
  EXPECT_EQ(lenient.skipped(), 1u);
}

TEST(Rawlog, GarbageFileIsACorruptRawlog) {
  test::TempDir tmp;
  test::writeText(tmp / "g.rawlog", std::string(5000, 'x'));
  const std::string msg =
      test::expectInputError([&] { openDataset(tmp / "g.rawlog"); }, "g.rawlog", "rawlog");
  EXPECT_LT(msg.size(), 300u);
}
