// ScanIterator with prefetch: the same scans, in the same order, with the same skips, warnings and
// errors as without it, whatever the reader throws; and an iterator left early stops its thread.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <thread>

#include "io_test_util.h"
#include "radarslam/core/errors.h"
#include "radarslam/io/dataset.h"

using namespace radarslam;

namespace {

// A dataset of n tiny scans whose i-th scan has stamp 1 s + i ms and power i; `faults` scripts
// what scan i does instead: "unreadable" (InputError), "inconsistent" (wrong power size),
// "duplicate" (the previous scan's stamp), "earlier" (an earlier stamp), "blank" (all zero),
// "crash" (a std::runtime_error that is not an InputError).
class ScriptedReader : public DatasetReader {
 public:
  ScriptedReader(std::size_t n, std::map<std::size_t, std::string> faults)
      : n_(n), faults_(std::move(faults)) {}
  DatasetKind kind() const override { return DatasetKind::Oxford; }
  const std::filesystem::path& root() const override { return root_; }
  std::string sensorName() const override { return "scripted"; }
  std::size_t size() const override { return n_; }
  StampNs indexStamp(std::size_t i) const override { return stamp(i); }
  std::filesystem::path scanPath(std::size_t i) const override { return "scan" + std::to_string(i); }
  const Trajectory& groundTruth() const override { return gt_; }
  CObservationRadarScan::Ptr readScan(std::size_t i) const override {
    ++reads;
    const auto f = faults_.find(i);
    const std::string fault = f == faults_.end() ? "" : f->second;
    if (fault == "unreadable") throw InputError(scanPath(i).string(), "truncated PNG");
    if (fault == "crash") throw std::runtime_error("reader crashed at scan " + std::to_string(i));
    auto scan = CObservationRadarScan::Create();
    scan->resize(4, 8);
    scan->range_resolution_m = 0.0432;
    StampNs t = stamp(i);
    if (fault == "duplicate") t = stamp(i - 1);
    if (fault == "earlier") t = stamp(i - 1) - 1;
    for (auto& s : scan->azimuth_stamps_ns) s = t;
    for (std::size_t a = 0; a < 4; ++a) scan->azimuth_angles_rad[a] = a * M_PI / 2;
    std::fill(scan->power.begin(), scan->power.end(),
              static_cast<std::uint8_t>(fault == "blank" ? 0 : i + 1));
    if (fault == "inconsistent") scan->power.resize(3);
    return scan;
  }
  mutable std::atomic<int> reads{0};

 private:
  static StampNs stamp(std::size_t i) { return 1'000'000'000 + static_cast<StampNs>(i) * 1'000'000; }
  std::size_t n_;
  std::map<std::size_t, std::string> faults_;
  std::filesystem::path root_ = "scripted";
  Trajectory gt_;
};

struct Pass {
  std::vector<std::size_t> indices;
  std::vector<std::uint8_t> first_power;
  std::size_t skipped = 0, blank = 0, duplicates = 0, unreadable = 0;
  std::string error;  // what() of the exception that ended the pass, if one did
};

Pass iterate(const DatasetReader& reader, bool skip, std::size_t prefetch, std::size_t first = 0,
             std::size_t end = static_cast<std::size_t>(-1)) {
  Pass p;
  ScanIterator it(reader, skip, first, end, prefetch);
  try {
    while (const auto s = it.next()) {
      p.indices.push_back(it.index());
      p.first_power.push_back(s->power.front());
    }
  } catch (const std::exception& e) {
    p.error = e.what();
  }
  p.skipped = it.skipped();
  p.blank = it.stats().blank;
  p.duplicates = it.stats().skipped_duplicate;
  p.unreadable = it.stats().skipped_unreadable;
  return p;
}

void expectSame(const Pass& a, const Pass& b) {
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.first_power, b.first_power);
  EXPECT_EQ(a.skipped, b.skipped);
  EXPECT_EQ(a.blank, b.blank);
  EXPECT_EQ(a.duplicates, b.duplicates);
  EXPECT_EQ(a.unreadable, b.unreadable);
  EXPECT_EQ(a.error, b.error);
}

}  // namespace

TEST(ScanPrefetch, SameScansSkipsAndCountsAsWithout) {
  const ScriptedReader reader(40, {{3, "unreadable"}, {7, "inconsistent"}, {12, "duplicate"}, {20, "blank"}});
  const Pass plain = iterate(reader, true, 0);
  ASSERT_EQ(plain.indices.size(), 37u);  // 3, 7 and 12 skipped
  EXPECT_EQ(plain.unreadable, 2u);
  EXPECT_EQ(plain.duplicates, 1u);
  EXPECT_EQ(plain.blank, 1u);
  for (const std::size_t depth : {1, 2, 4, 64}) {
    SCOPED_TRACE("prefetch " + std::to_string(depth));
    expectSame(iterate(reader, true, depth), plain);
    expectSame(iterate(reader, true, depth, 5, 30), iterate(reader, true, 0, 5, 30));
  }
}

TEST(ScanPrefetch, ErrorsEndThePassAtTheSameScan) {
  for (const auto& fault : {"unreadable", "inconsistent", "earlier"}) {
    SCOPED_TRACE(fault);
    const ScriptedReader reader(20, {{9, fault}});
    const Pass plain = iterate(reader, false, 0);
    EXPECT_EQ(plain.indices.size(), 9u);
    EXPECT_NE(plain.error.find("scan9"), std::string::npos) << plain.error;
    expectSame(iterate(reader, false, 4), plain);
  }
  // An error that is not about the input is not skipped, with or without prefetch.
  const ScriptedReader crashing(20, {{5, "crash"}});
  const Pass plain = iterate(crashing, true, 0);
  EXPECT_EQ(plain.error, "reader crashed at scan 5");
  expectSame(iterate(crashing, true, 4), plain);
}

TEST(ScanPrefetch, ReadsAtMostDepthAheadAndStopsWhenLeftEarly) {
  const ScriptedReader reader(1000, {});
  {
    ScanIterator it(reader, false, 0, 1000, 3);
    ASSERT_TRUE(it.next());
    ASSERT_TRUE(it.next());
    // Two taken and 3 waiting: the reader waits for room before it reads the next one.
    for (int wait = 0; wait < 2000 && reader.reads < 5; ++wait)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(reader.reads, 5);
  }  // destroyed with 995 scans unread: must not hang or read on
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(reader.reads, 5);
  // An empty range starts no thread and returns nothing.
  ScanIterator empty(reader, false, 10, 10, 4);
  EXPECT_FALSE(empty.next());
}
