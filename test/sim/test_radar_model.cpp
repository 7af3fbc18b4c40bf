// Radar physics: determinism, motion distortion, antenna pattern, weather, config loading.
#include <gtest/gtest.h>

#include <iostream>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "radarslam/core/errors.h"
#include "radarslam/io/oxford_writer.h"
#include "radarslam/sim/radar_model.h"
#include "radarslam/sim/simulator.h"
#include "sim_test_util.h"
#include "temp_dir.h"

using namespace radarslam;
using namespace radarslam::sim;

namespace {
constexpr StampNs kStart = 1'600'000'000LL * kNsPerSec;

/// A straight drive along +x at `speed` m/s (0 = parked at the origin).
Route straightRoute(double speed) {
  Route r;
  r.start_stamp = kStart;
  if (speed <= 0) {
    r.samples.push_back({0, 0, 1e6, 0, 0, 0, 0});
    return r;
  }
  for (double s = 0; s <= 400; s += 0.25) r.samples.push_back({s, s / speed, s / speed, s, 0, 0, speed});
  return r;
}

World emptyWorld() {
  World w;
  w.seed = 5;
  w.street_x = {0, 100}, w.street_y = {0, 100};
  return w;
}

int peakBin(const CObservationRadarScan& scan, std::size_t az) {
  const auto row = scan.row(az);
  return static_cast<int>(std::max_element(row.begin() + 20, row.end()) - row.begin());
}

/// Mean code over the azimuths within [min_angle_deg, max_angle_deg] and the ranges within
/// [min_range, max_range].
double meanCode(const CObservationRadarScan& s, double min_angle_deg, double max_angle_deg, double min_range,
                double max_range = std::numeric_limits<double>::infinity()) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t a = 0; a < s.num_azimuths; ++a) {
    double deg = std::remainder(s.azimuth_angles_rad[a], 2 * M_PI) * 180 / M_PI;
    if (deg < min_angle_deg || deg > max_angle_deg) continue;
    for (std::size_t b = 0; b < s.num_bins; ++b)
      if (s.binRange(b) >= min_range && s.binRange(b) <= max_range) sum += s.row(a)[b], ++n;
  }
  return sum / static_cast<double>(n);
}

/// Fraction of code-0 bins (amplitude below the 8-bit step) at ranges >= min_range.
double zeroFraction(const CObservationRadarScan& s, double min_range) {
  std::size_t zeros = 0, n = 0;
  for (std::size_t a = 0; a < s.num_azimuths; ++a)
    for (std::size_t b = 0; b < s.num_bins; ++b)
      if (s.binRange(b) >= min_range) zeros += s.row(a)[b] == 0, ++n;
  return static_cast<double>(zeros) / static_cast<double>(n);
}
}  // namespace

TEST(SimRadar, SameSeedGivesByteIdenticalPngsOtherSeedDoesNot) {
  Simulation a(simtest::smallConfig(11)), b(simtest::smallConfig(11)), c(simtest::smallConfig(12));
  CObservationRadarScan sa, sb, sc;
  for (std::size_t i : {0u, 3u}) {
    a.render(i, sa), b.render(i, sb), c.render(i, sc);
    EXPECT_EQ(encodeOxfordPng(sa), encodeOxfordPng(sb)) << "scan " << i;
    EXPECT_NE(sa.power, sc.power);
  }
}

TEST(SimRadar, GeometryAndStampsFollowTheSensor) {
  Simulation sim(simtest::smallConfig(1, 3));
  CObservationRadarScan s;
  sim.render(1, s);
  ASSERT_EQ(s.checkConsistency(), "");
  EXPECT_EQ(s.num_azimuths, 100u);
  EXPECT_EQ(s.num_bins, 600u);
  EXPECT_EQ(s.azimuth_stamps_ns.front(), sim.scanStart(1));
  EXPECT_EQ(sim.scanStart(1) - sim.scanStart(0), 250'000'000);
  for (std::size_t i = 1; i < s.num_azimuths; ++i) {
    EXPECT_EQ(s.azimuth_stamps_ns[i] - s.azimuth_stamps_ns[i - 1], 2'500'000);  // 250 ms / 100, whole us
    EXPECT_GT(s.azimuth_angles_rad[i], s.azimuth_angles_rad[i - 1]);
  }
  // Oxford encoders for 400 azimuths: 13, 27, ..., 5599.
  RadarGeometry oxford;
  EXPECT_EQ(oxford.encoder(0), 13);
  EXPECT_EQ(oxford.encoder(1), 27);
  EXPECT_EQ(oxford.encoder(399), 5599);
}

TEST(SimRadar, EachAzimuthFiresFromItsOwnPose) {
  // A wall 60 m ahead across the road; driving at 10 m/s, the last azimuth (also pointing ahead)
  // fires ~0.25 s after the first, 2.5 m closer to the wall: motion distortion.
  World w = emptyWorld();
  Surface wall;
  wall.reflectivity = 1, wall.roughness = 1, wall.texture_period_m = 1000;
  w.segments.push_back({{60, -300}, {60, 300}, wall});
  w.buildIndex();
  RadarGeometry g;
  g.azimuths = 100, g.bins = 1000, g.range_resolution_m = 0.1;
  for (double speed : {0.0, 10.0}) {
    const Route route = straightRoute(speed);
    RadarRenderer renderer(w, route, g, {}, weatherPreset("clear"), 1);
    CObservationRadarScan s;
    const StampNs start = kStart + kNsPerSec;
    renderer.render(start, 0, s);
    const double x0 = route.poseAt(s.azimuth_stamps_ns.front()).x,
                 x1 = route.poseAt(s.azimuth_stamps_ns.back()).x;
    const double r_first = (60 - x0) / std::cos(s.azimuth_angles_rad.front());
    const double r_last = (60 - x1) / std::cos(s.azimuth_angles_rad.back());
    EXPECT_NEAR(s.binRange(peakBin(s, 0)), r_first, 0.25) << "speed " << speed;
    EXPECT_NEAR(s.binRange(peakBin(s, 99)), r_last, 0.25) << "speed " << speed;
    if (speed > 0) {
      EXPECT_NEAR(x1 - x0, speed * 0.2475, 1e-3);
    }
  }
}

TEST(SimRadar, BeamSpreadsAPoleOverNeighbouringAzimuthsOnly) {
  World w = emptyWorld();
  RadarGeometry g;  // 400 azimuths, 0.9 deg apart; 1.8 deg beam
  g.bins = 1000;
  const double angle = g.angle(200);
  Surface pole;
  pole.reflectivity = 2, pole.roughness = 0.3f, pole.texture_period_m = 1000;
  w.circles.push_back({{30 * std::cos(angle), 30 * std::sin(angle)}, 0.15, pole});
  w.buildIndex();
  const Route route = straightRoute(0);
  RadarRenderer renderer(w, route, g, {}, weatherPreset("clear"), 3);
  CObservationRadarScan s;
  renderer.render(kStart, 0, s);
  const auto bin = static_cast<std::size_t>(29.85 / g.range_resolution_m);
  auto peak = [&](std::size_t az) {
    int m = 0;
    for (std::size_t b = bin - 10; b < bin + 10; ++b) m = std::max<int>(m, s.row(az)[b]);
    return m;
  };
  EXPECT_GT(peak(200), 80);
  EXPECT_GT(peak(199), 60);  // one azimuth step = half the beam width
  EXPECT_GT(peak(201), 60);
  EXPECT_LT(peak(215), 40);  // 13.5 deg away: past the sidelobes
  EXPECT_LT(peak(185), 40);
}

TEST(SimRadar, SnowBlanksTheFrontAndFogRaisesTheFloor) {
  auto render = [](const std::string& weather) {
    auto c = simtest::smallConfig(21, 60);
    c.weather = weather;
    Simulation sim(c);
    CObservationRadarScan s;
    sim.render(50, s);  // driving through the city
    return s;
  };
  const auto clear = render("clear"), snow = render("snow"), fog = render("fog");
  // Front half (azimuths within +-90 deg of straight ahead) lost in snow; the back is kept.
  EXPECT_LT(meanCode(snow, -80, 80, 3), 0.5 * meanCode(clear, -80, 80, 3));
  EXPECT_GT(meanCode(snow, 100, 180, 3) + meanCode(snow, -180, -100, 3),
            0.7 * (meanCode(clear, 100, 180, 3) + meanCode(clear, -180, -100, 3)));
  // Fog raises the noise floor: far away, fewer bins fall below the 8-bit step. (Measured on the
  // floor itself; the far mean code is dominated by echoes since the Oxford calibration, and fog
  // attenuates those.)
  std::cout << "far zero fraction clear " << zeroFraction(clear, 80) << " fog " << zeroFraction(fog, 80)
            << "; far mean code clear " << meanCode(clear, -180, 180, 80) << " fog "
            << meanCode(fog, -180, 180, 80) << "\n";
  EXPECT_LT(zeroFraction(fog, 80), 0.8 * zeroFraction(clear, 80));
  EXPECT_THROW(weatherPreset("hail"), InputError);
}

TEST(SimRadar, FogRaisesOnlyTheFloorRainAddsNearRangeClutter) {
  // An empty world seen by a parked radar: all that is rendered is the noise floor and what the
  // weather adds. Fog droplets are Rayleigh scatterers ~60 dB weaker than heavy rain, so fog may
  // raise the floor at every range alike; rain's backscatter lifts the first tens of metres over
  // the far floor. Measured as the mean code at 12-30 m (past the STC) minus that at 100-150 m.
  World w = emptyWorld();
  w.buildIndex();
  RadarGeometry g;
  g.azimuths = 100, g.bins = 3500;        // 0.0438 m bins: out to 153 m
  const Route parked = straightRoute(0);  // the renderer keeps references to world and route
  auto nearOverFar = [&](const Weather& weather) {
    RadarRenderer renderer(w, parked, g, {}, weather, 7);
    CObservationRadarScan s;
    renderer.render(kStart, 0, s);
    return meanCode(s, -180, 180, 12, 30) - meanCode(s, -180, 180, 100, 150);
  };
  const double clear = nearOverFar(weatherPreset("clear"));
  const double fog = nearOverFar(weatherPreset("fog")) - clear;
  const double rain = nearOverFar(weatherPreset("rain")) - clear;
  Weather fog_with_clutter = weatherPreset("fog");  // what the fog preset drew until 2026-12-07
  fog_with_clutter.volume_clutter_power = 40, fog_with_clutter.volume_clutter_range_m = 25;
  const double cluttered = nearOverFar(fog_with_clutter) - clear;
  std::cout << "near-range code lift over clear (near minus far): fog " << fog << ", rain " << rain
            << ", fog with volume clutter " << cluttered << "\n";
  EXPECT_LT(std::abs(fog), 0.5);
  EXPECT_GT(rain, 1.0);  // the measure sees clutter where there is some
  EXPECT_GT(cluttered, 1.0);
}

TEST(SimConfig, ShippedYamlMatchesDefaultsAndRejectsTypos) {
  SimulationConfig defaults, loaded;
  loadSimulationConfig(std::string(RADARSLAM_SOURCE_DIR) + "/config/sim.yaml", loaded);
  EXPECT_EQ(loaded.geometry.azimuths, defaults.geometry.azimuths);
  EXPECT_EQ(loaded.geometry.bins, defaults.geometry.bins);
  EXPECT_DOUBLE_EQ(loaded.physics.power_scale, defaults.physics.power_scale);
  EXPECT_DOUBLE_EQ(loaded.physics.beam_width_deg, defaults.physics.beam_width_deg);
  EXPECT_DOUBLE_EQ(loaded.route.country_speed_mps, defaults.route.country_speed_mps);
  EXPECT_EQ(loaded.world.blocks_x, defaults.world.blocks_x);
  test::TempDir dir;
  std::ofstream(dir / "bad.yaml") << "physics:\n  beam_widht_deg: 2\n";
  EXPECT_THROW(loadSimulationConfig((dir / "bad.yaml").string(), loaded), InputError);
  std::ofstream(dir / "fast.yaml") << "route:\n  city_speed_mps: 20\n";
  EXPECT_THROW(loadSimulationConfig((dir / "fast.yaml").string(), loaded), InputError);
}
