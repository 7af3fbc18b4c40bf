// The simulator's FMCW Doppler range offset (RadarGeometry::doppler_beta_s, chirp) and its removal by
// the radar module (radar/doppler_compensation.h): a wall ahead while driving at a known speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/radar/doppler_compensation.h"
#include "radarslam/sim/radar_model.h"

using namespace radarslam;
using namespace radarslam::sim;

namespace {
constexpr StampNs kDriveStart = 1'600'000'000LL * kNsPerSec;
constexpr double kSpeed = 10.0;

Route straightRoute() {  // along +x at kSpeed
  Route r;
  r.start_stamp = kDriveStart;
  for (double s = 0; s <= 400; s += 0.25) r.samples.push_back({s, s / kSpeed, s / kSpeed, s, 0, 0, kSpeed});
  return r;
}

World wallAhead() {  // a wall across the road 60 m ahead
  World w;
  w.seed = 5;
  w.street_x = {0, 100}, w.street_y = {0, 100};
  Surface wall;
  wall.reflectivity = 1, wall.roughness = 1, wall.texture_period_m = 1000;
  w.segments.push_back({{60, -300}, {60, 300}, wall});
  w.buildIndex();
  return w;
}

double peakRange(const CObservationRadarScan& scan, std::size_t az) {
  const auto row = scan.row(az);
  return scan.binRange(static_cast<std::size_t>(std::max_element(row.begin() + 20, row.end()) - row.begin()));
}

CObservationRadarScan render(double beta, const std::string& chirp) {
  const World w = wallAhead();
  const Route route = straightRoute();
  RadarGeometry g;
  g.azimuths = 100, g.bins = 1000, g.range_resolution_m = 0.1;
  g.doppler_beta_s = beta;
  g.chirp = chirp;
  RadarRenderer renderer(w, route, g, {}, weatherPreset("clear"), 1);
  CObservationRadarScan s;
  renderer.render(kDriveStart + kNsPerSec, 0, s);
  return s;
}
}  // namespace

TEST(SimDoppler, OffsetIsModelledPerChirpAndRemovedByTheCompensation) {
  constexpr double kBeta = 0.1;  // 1 m at 10 m/s: ten bins, well above the 0.25 m peak tolerance
  const CObservationRadarScan truth = render(0.0, "single");
  EXPECT_FALSE(truth.hasChirpDirections());
  for (const std::string chirp : {"single", "alternating"}) {
    SCOPED_TRACE(chirp);
    CObservationRadarScan s = render(kBeta, chirp);
    EXPECT_EQ(s.hasChirpDirections(), chirp == "alternating");
    // Azimuths 0 and 1 both look at the wall (0 and 3.6 deg); 0 is an up-chirp, 1 a down-chirp
    // when alternating: nearer by beta * v * cos(theta), or farther by as much.
    for (const std::size_t az : {0u, 1u}) {
      const double expected_shift =
          (chirp == "alternating" && az == 1 ? -1 : 1) * kBeta * kSpeed * std::cos(s.azimuth_angles_rad[az]);
      EXPECT_NEAR(peakRange(truth, az) - peakRange(s, az), expected_shift, 0.25) << "azimuth " << az;
    }
    compensateDoppler(s, {kSpeed, 0.0, 0.0}, kBeta);
    for (const std::size_t az : {0u, 1u, 99u})
      EXPECT_NEAR(peakRange(s, az), peakRange(truth, az), 0.25) << "azimuth " << az;
  }
}

TEST(SimDoppler, ZeroBetaRendersTheSameBytesAndChirpIsValidated) {
  // beta 0 (every shipped simulator config but the measurement) leaves the scan untouched.
  const CObservationRadarScan a = render(0.0, "single"), b = render(0.0, "alternating");
  EXPECT_EQ(a.power, b.power);
  RadarGeometry g;
  EXPECT_THROW(loadGeometry(YamlParams::fromText("chirp: triangle\n"), g), InputError);
  loadGeometry(YamlParams::fromText("chirp: alternating\ndoppler_beta_s: 0.049\n"), g);
  EXPECT_EQ(g.chirp, "alternating");
  EXPECT_DOUBLE_EQ(g.doppler_beta_s, 0.049);
}
