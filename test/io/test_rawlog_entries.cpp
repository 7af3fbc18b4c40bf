// Which rawlog entries the reader deserialises (io/rawlog_entries.h): radar scans alone or in
// sensory frames, and nullptr entries; any other class is refused by name before MRPT runs its
// deserialiser, and a sensory frame's count from the file allocates nothing.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "io_test_util.h"
#include "radarslam/io/dataset.h"
#include "radarslam/obs/registration.h"
#include "temp_dir.h"

using namespace radarslam;

namespace {
CObservationRadarScan::Ptr scanLabelled(const std::string& label, int azimuths) {
  auto scan = CObservationRadarScan::Create();
  scan->resize(azimuths, 13);
  scan->sensorLabel = label;
  for (int a = 0; a < azimuths; ++a) {
    scan->azimuth_stamps_ns[a] = 1'000'000'000 + 1000 * a;
    scan->azimuth_angles_rad[a] = 6.283 * a / azimuths;
    scan->azimuth_valid[a] = 1;
  }
  return scan;
}

// Writes the objects (nullptr for a nullptr entry) as a gzip rawlog, the way MRPT's tools do.
void writeRawlog(const std::filesystem::path& file,
                 const std::vector<const mrpt::serialization::CSerializable*>& objects) {
  registerRadarslamClasses();
  mrpt::io::CFileGZOutputStream out(file.string());
  auto archive = mrpt::serialization::archiveFrom(out);
  for (const auto* o : objects) archive.WriteObject(o);
}

// The header MRPT writes for an object of the named class and version (new format).
std::string header(const std::string& class_name, std::uint8_t version) {
  return std::string(1, static_cast<char>(0x80 | class_name.size())) + class_name +
         static_cast<char>(version);
}
}  // namespace

TEST(RawlogEntries, ScansAloneInSensoryFramesAndNullEntriesAreRead) {
  test::TempDir tmp;
  const auto a = scanLabelled("a", 5), b = scanLabelled("b", 6), c = scanLabelled("c", 7);
  mrpt::obs::CSensoryFrame frame, empty_frame;
  frame.insert(b);
  frame.insert(c);
  writeRawlog(tmp / "mixed.rawlog", {a.get(), nullptr, &frame, &empty_frame});
  const auto reader = openDataset(tmp / "mixed.rawlog");
  ASSERT_EQ(reader->size(), 3u);
  EXPECT_EQ(reader->sensorName(), "a (rawlog)");
  // Out of order: the frame's second scan, then back to the first entry, then the frame's first.
  EXPECT_EQ(reader->readScan(2)->sensorLabel, "c");
  EXPECT_EQ(reader->readScan(2)->num_azimuths, 7u);
  EXPECT_EQ(reader->readScan(0)->num_azimuths, 5u);
  EXPECT_EQ(reader->readScan(1)->sensorLabel, "b");
  EXPECT_EQ(reader->readScan(1)->num_azimuths, 6u);
}

TEST(RawlogEntries, OtherClassesAreRefusedByNameAtTopLevelAndInFrames) {
  test::TempDir tmp;
  const auto scan = scanLabelled("radar", 5);
  mrpt::obs::CObservationOdometry odometry;
  writeRawlog(tmp / "odo.rawlog", {scan.get(), &odometry});
  test::expectInputError([&] { openDataset(tmp / "odo.rawlog"); }, "odo.rawlog",
                         "entry 1 is a mrpt::obs::CObservationOdometry: radarslam reads only");
  mrpt::obs::CSensoryFrame frame;
  frame.insert(scan);
  frame.insert(mrpt::obs::CObservationComment::Create());
  writeRawlog(tmp / "comment.rawlog", {&frame});
  test::expectInputError([&] { openDataset(tmp / "comment.rawlog"); }, "comment.rawlog",
                         "entry 0 is a mrpt::obs::CObservationComment");
  test::writeText(tmp / "unknown.rawlog", header("NoSuchClass", 0) + "\x88");
  test::expectInputError([&] { openDataset(tmp / "unknown.rawlog"); }, "unknown.rawlog",
                         "corrupt rawlog at entry 0: unknown class 'NoSuchClass'");
}

// MRPT's own CSensoryFrame deserialiser resizes its observation list to the uint32 count of the
// file before reading one: 2^32 - 1 observations were a 64 GiB allocation (std::bad_alloc),
// 0x0C000000 the 3 GiB one fuzz_rawlog found. Now the count only bounds a loop over the file.
TEST(RawlogEntries, SensoryFrameClaimingBillionsOfObservationsIsATruncatedFile) {
  test::TempDir tmp;
  for (const std::string& count : {std::string("\xff\xff\xff\xff", 4), std::string("\0\0\0\x0c", 4)}) {
    test::writeText(tmp / "frame.rawlog", header("mrpt::obs::CSensoryFrame", 2) + count);
    test::expectInputError([&] { openDataset(tmp / "frame.rawlog"); }, "frame.rawlog",
                           "truncated rawlog: entry 0 ends early");
  }
  test::writeText(tmp / "v9.rawlog", header("mrpt::obs::CSensoryFrame", 9) + std::string(4, '\0') + "\x88");
  test::expectInputError([&] { openDataset(tmp / "v9.rawlog"); }, "v9.rawlog",
                         "mrpt::obs::CSensoryFrame version 9");
}

TEST(RawlogEntries, HeaderDamageIsACorruptRawlog) {
  test::TempDir tmp;
  test::writeText(tmp / "long.rawlog", std::string(1, '\xff') + std::string(200, 'x'));
  test::expectInputError([&] { openDataset(tmp / "long.rawlog"); }, "long.rawlog", "class name of 127 bytes");
  test::writeText(tmp / "flag.rawlog", header("nullptr", 0).substr(0, 8) + "\x77");
  test::expectInputError([&] { openDataset(tmp / "flag.rawlog"); }, "flag.rawlog",
                         "end-of-object flag missing after a nullptr");
}
