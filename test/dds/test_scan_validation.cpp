// Every live RadarScan sample passes ScanStreamFilter (docs/dds.md "Radar scan input"): samples
// a file reader would reject (stamps zero or backwards, too few azimuths or bins, an absurd
// resolution, mismatched arrays) and samples not after the previous one are dropped with a
// rate-limited warning, and the stream goes on.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include <radarslam/core/errors.h>
#include <radarslam/dds/domain.h>
#include <radarslam/dds/scan_messages.h>
#include <radarslam/dds/scan_stream_filter.h>
#include <radarslam/dds/scan_subscriber.h>
#include <radarslam/obs/scan_checks.h>

#include "dds_test_util.h"

namespace radarslam {
namespace {

constexpr StampNs kT0 = 1'600'000'000'000'000'000LL;

// A plausible 64 x 32 sample whose first azimuth is at kT0 + i * 250 ms.
dds::RadarScanMsg sample(int i) {
  CObservationRadarScan scan;
  scan.resize(64, 32);
  scan.range_resolution_m = 0.0438;
  scan.range_offset_m = 0.0219;
  for (std::size_t k = 0; k < scan.power.size(); ++k) scan.power[k] = static_cast<std::uint8_t>(k * 7);
  for (std::uint32_t a = 0; a < 64; ++a)
    scan.azimuth_stamps_ns[a] = kT0 + i * 250'000'000LL + a * 3'900'000LL;
  scan.updateReferenceTime();
  return dds::scanMessage(scan, "radar");
}

// The problem ScanStreamFilter reports for sample(1) after `corrupt` ("" if accepted).
std::string problemOf(const std::function<void(dds::RadarScanMsg&)>& corrupt) {
  dds::ScanStreamFilter filter("rt/test");
  dds::RadarScanMsg m = sample(1);
  corrupt(m);
  return filter.accept(m) ? "" : filter.lastProblem();
}

void resizeAzimuths(dds::RadarScanMsg& m, std::uint32_t n) {
  m.num_azimuths = n;
  m.azimuth_stamps_ns.resize(n);
  m.azimuth_angles.resize(n);
  m.azimuth_valid.resize(n);
  m.power.resize(static_cast<std::size_t>(n) * m.num_bins);
}

TEST(ScanValidation, APlausibleSampleIsAccepted) {
  EXPECT_EQ(problemOf([](dds::RadarScanMsg&) {}), "");
}

TEST(ScanValidation, BadStampsAreRejected) {
  EXPECT_NE(problemOf([](auto& m) {
              std::fill(m.azimuth_stamps_ns.begin(), m.azimuth_stamps_ns.end(), 0);
            }).find("is not a UNIX time"),
            std::string::npos);
  EXPECT_NE(problemOf([](auto& m) {
              std::reverse(m.azimuth_stamps_ns.begin(), m.azimuth_stamps_ns.end());
            }).find("azimuth 1 stamp goes backwards"),
            std::string::npos);
  EXPECT_NE(problemOf([](auto& m) { m.azimuth_stamps_ns.back() += 60 * kNsPerSec; }).find("sweep lasts"),
            std::string::npos);
}

TEST(ScanValidation, ImplausibleGeometryIsRejected) {
  EXPECT_NE(problemOf([](auto& m) { resizeAzimuths(m, 2); }).find("2 azimuths"), std::string::npos);
  EXPECT_NE(problemOf([](auto& m) {
              m.num_bins = 1;
              m.power.resize(m.num_azimuths);
            }).find("1 range bins"),
            std::string::npos);
  for (double res : {1e300, 0.0, -0.04, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    const std::string p = problemOf([&](auto& m) { m.range_resolution = res; });
    EXPECT_NE(p.find("range resolution"), std::string::npos) << res << ": " << p;
  }
  EXPECT_NE(problemOf([](auto& m) { m.range_offset = 1e300; }).find("range offset"), std::string::npos);
  EXPECT_NE(problemOf([](auto& m) { m.azimuth_angles[3] = std::nan(""); }).find("not finite"),
            std::string::npos);
}

TEST(ScanValidation, MismatchedArraysAreRejected) {
  EXPECT_NE(problemOf([](auto& m) { m.power.pop_back(); }).find("array sizes"), std::string::npos);
  EXPECT_NE(problemOf([](auto& m) { m.azimuth_valid.push_back(1); }).find("array sizes"), std::string::npos);
  EXPECT_NE(problemOf([](auto& m) { m.num_azimuths = 0; }).find("array sizes"), std::string::npos);
  EXPECT_NE(problemOf([](auto& m) { m.num_bins = 1u << 31; }).find("array sizes"), std::string::npos);
}

TEST(ScanValidation, StampsNotAfterThePreviousScanAreDroppedAndTheStreamGoesOn) {
  dds::ScanStreamFilter filter("rt/radarslam/radar_scan");
  ASSERT_TRUE(filter.accept(sample(2)));
  EXPECT_FALSE(filter.accept(sample(2)));  // the same time again
  EXPECT_NE(filter.lastProblem().find("is not after the previous scan"), std::string::npos);
  EXPECT_FALSE(filter.accept(sample(1)));  // back in time
  dds::RadarScanMsg bad = sample(3);
  bad.range_resolution = 0;
  EXPECT_FALSE(filter.accept(bad));
  const auto good = filter.accept(sample(3));  // a bad sample does not end the stream
  ASSERT_TRUE(good);
  EXPECT_EQ(good->refStampNs(), sample(3).azimuth_stamps_ns[0] / 2 + sample(3).azimuth_stamps_ns[63] / 2);
  EXPECT_EQ(filter.accepted(), 2u);
  EXPECT_EQ(filter.dropped(), 3u);
  EXPECT_EQ(filter.warnings(), 1u);  // rate-limited: one warning for the burst
}

TEST(ScanValidation, WarningsAreRateLimited) {
  dds::ScanStreamFilter filter("rt/test", std::chrono::milliseconds(0));
  dds::RadarScanMsg bad = sample(1);
  bad.num_bins = 1;
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(filter.accept(bad));
  EXPECT_EQ(filter.warnings(), 3u);  // interval 0: every drop is reported
  dds::ScanStreamFilter quiet("rt/test", std::chrono::hours(1));
  for (int i = 0; i < 50; ++i) EXPECT_FALSE(quiet.accept(bad));
  EXPECT_EQ(quiet.warnings(), 1u);
  EXPECT_EQ(quiet.dropped(), 50u);
}

TEST(ScanValidation, ScanFromMessageThrowsInputErrorForImplausibleSamples) {
  dds::RadarScanMsg m = sample(1);
  m.range_resolution = 1e300;
  EXPECT_THROW(dds::scanFromMessage(m), InputError);
  EXPECT_NO_THROW(dds::scanFromMessage(sample(1)));
}

TEST(ScanValidation, ScanSubscriberHandsOutOnlyTheValidSamples) {
  using namespace std::chrono_literals;
  dds::Domain dom(test::testDomainId(17));
  dds::ScanSubscriber sub(dom, dds::kRadarScanTopic, 16);
  dds::Publisher<dds::RadarScanMsg> pub(dom, dds::kRadarScanTopic, dds::TopicQos::stream(16));
  ASSERT_TRUE(pub.waitForSubscriptions(1, 5s));
  dds::RadarScanMsg zero = sample(1);
  std::fill(zero.azimuth_stamps_ns.begin(), zero.azimuth_stamps_ns.end(), 0);
  pub.publish(zero);       // stamps at t = 0
  pub.publish(sample(2));  // good
  pub.publish(sample(1));  // back in time
  pub.publish(sample(3));  // good
  const auto a = sub.next(5s), b = sub.next(5s);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->azimuth_stamps_ns[0], sample(2).azimuth_stamps_ns[0]);
  EXPECT_EQ(b->azimuth_stamps_ns[0], sample(3).azimuth_stamps_ns[0]);
  EXPECT_FALSE(sub.next(50ms));
  EXPECT_EQ(sub.filter().dropped(), 2u);
  EXPECT_EQ(sub.filter().accepted(), 2u);
}

}  // namespace
}  // namespace radarslam
