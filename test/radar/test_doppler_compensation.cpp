// Doppler range offset removal (radar/doppler_compensation.h): sign convention, per-azimuth chirp
// sign, image rows and point clouds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/radar/doppler_compensation.h"
#include "synthetic_scan.h"

using namespace radarslam;

namespace {
constexpr double kPi = std::numbers::pi;

std::size_t peakBin(const CObservationRadarScan& s, std::size_t azimuth) {
  const auto row = s.row(azimuth);
  return static_cast<std::size_t>(std::max_element(row.begin(), row.end()) - row.begin());
}
}  // namespace

TEST(DopplerOffset, ClosingTargetsAppearNearerOnAnUpChirp) {
  const BodyVelocity forward{10.0, 0.0, 0.0};
  EXPECT_NEAR(dopplerRangeOffset(0.05, 1, forward, 0.0), 0.5, 1e-12);              // ahead: 0.5 m nearer
  EXPECT_NEAR(dopplerRangeOffset(0.05, 1, forward, kPi), -0.5, 1e-12);             // behind: farther
  EXPECT_NEAR(dopplerRangeOffset(0.05, 1, forward, kPi / 2), 0.0, 1e-12);          // abeam: none
  EXPECT_NEAR(dopplerRangeOffset(0.05, -1, forward, 0.0), -0.5, 1e-12);            // down-chirp: opposite
  EXPECT_NEAR(dopplerRangeOffset(0.05, 1, {0.0, 4.0, 0.0}, kPi / 2), 0.2, 1e-12);  // v_y along +y
  // v_r = v_x cos(phi) + v_y sin(phi)
  EXPECT_NEAR(dopplerRangeOffset(0.049, 1, {3.0, -2.0, 0.3}, 0.7),
              0.049 * (3 * std::cos(0.7) - 2 * std::sin(0.7)), 1e-12);
}

TEST(DopplerOffset, UnknownChirpCountsAsUpChirp) {
  auto s = test::makeScan(4, 10);
  EXPECT_EQ(chirpSign(s, 0), 1);
  s.azimuth_chirp = {1, -1, 0, -1};
  EXPECT_EQ(chirpSign(s, 0), 1);
  EXPECT_EQ(chirpSign(s, 1), -1);
  EXPECT_EQ(chirpSign(s, 2), 1);
  s.azimuth_chirp.clear();
  EXPECT_EQ(chirpSign(s, 3), 1);
}

// A wall ahead, driving forward at 10 m/s, beta 0.05 s: measured 0.5 m short on up-chirps and 0.5 m
// long on down-chirps; after compensation every azimuth has it back at its true range.
TEST(DopplerCompensation, ImageRowsGetTheirTrueRangeBackForBothChirps) {
  constexpr double kRes = 0.1, kTrue = 40.0, kBeta = 0.05;
  const BodyVelocity v{10.0, 0.0, 0.0};
  for (const bool alternating : {false, true}) {
    auto s = test::makeScan(8, 800, kRes);
    // Azimuths 0 and 1 point ahead-ish (0 and 45 deg), the rest elsewhere.
    for (std::size_t a = 0; a < 8; ++a) {
      if (alternating) s.azimuth_chirp[a] = a % 2 ? -1 : 1;
      const double measured = kTrue - dopplerRangeOffset(kBeta, chirpSign(s, a), v, s.azimuth_angles_rad[a]);
      s.row(a)[static_cast<std::size_t>(std::lround(measured / kRes))] = 200;
    }
    const auto before0 = peakBin(s, 0);
    EXPECT_EQ(before0, static_cast<std::size_t>(std::lround((kTrue - 0.5) / kRes)));
    if (alternating) {
      EXPECT_EQ(peakBin(s, 1),
                static_cast<std::size_t>(std::lround((kTrue + 0.5 * std::cos(kPi / 4)) / kRes)));
    }
    compensateDoppler(s, v, kBeta);
    for (std::size_t a = 0; a < 8; ++a)
      EXPECT_NEAR(s.binRange(peakBin(s, a)), kTrue, kRes)
          << "azimuth " << a << (alternating ? " alternating" : "");
  }
}

TEST(DopplerCompensation, WholeBinShiftKeepsPowerAndZeroBetaIsANoOp) {
  auto s = test::makeScan(2, 100, 0.1);
  s.row(0)[50] = 123;  // azimuth 0 (ahead): shift by 0.05 * 20 = 1.0 m = 10 bins outwards
  s.row(1)[50] = 77;   // azimuth 1 (behind): 10 bins inwards
  auto unchanged = s;
  compensateDoppler(unchanged, {20.0, 0.0, 0.0}, 0.0);
  EXPECT_EQ(unchanged.power, s.power);
  compensateDoppler(unchanged, {}, 0.05);
  EXPECT_EQ(unchanged.power, s.power);
  compensateDoppler(s, {20.0, 0.0, 0.0}, 0.05);
  EXPECT_EQ(s.row(0)[60], 123);
  EXPECT_EQ(s.row(0)[50], 0);
  EXPECT_EQ(s.row(1)[40], 77);
  EXPECT_EQ(s.row(1)[99], 0);  // shifted in from beyond the last bin
}

TEST(DopplerCompensation, PointsMoveOutAlongTheirBeam) {
  auto s = test::makeScan(4, 10);  // angles 0, 90, 180, 270 deg
  s.azimuth_chirp = {1, 1, -1, 0};
  std::vector<RadarPoint> pts(3);
  pts[0].azimuth = 0, pts[0].range_m = 20, pts[0].x = 20;
  pts[1].azimuth = 2, pts[1].range_m = 20, pts[1].x = -20;  // behind, down-chirp: farther -> nearer
  pts[2].azimuth = 1, pts[2].range_m = 5, pts[2].y = 5;
  compensateDoppler(pts, s, {10.0, 2.0, 0.0}, 0.05);
  EXPECT_NEAR(pts[0].range_m, 20.5, 1e-5);
  EXPECT_NEAR(pts[0].x, 20.5, 1e-5);
  EXPECT_NEAR(pts[1].range_m, 20.5, 1e-5);  // s = -1, v_r = -10: +0.5
  EXPECT_NEAR(pts[1].x, -20.5, 1e-5);
  EXPECT_NEAR(pts[2].range_m, 5.1, 1e-5);  // v_y = 2 along the beam
  EXPECT_NEAR(pts[2].y, 5.1, 1e-5);
  std::vector<RadarPoint> bad(1);
  bad[0].azimuth = 4;
  EXPECT_THROW(compensateDoppler(bad, s, {1.0, 0.0, 0.0}, 0.05), InputError);
}

TEST(DopplerParams, LoadedWithRange) {
  DopplerParams p;
  loadParams(YamlParams::fromText("enabled: true\nbeta_s: 0.02\n"), p);
  EXPECT_TRUE(p.enabled);
  EXPECT_DOUBLE_EQ(p.beta_s, 0.02);
  EXPECT_THROW(loadParams(YamlParams::fromText("beta_s: 1.5\n"), p), InputError);
}
