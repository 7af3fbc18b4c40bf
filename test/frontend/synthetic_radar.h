#pragma once
// Test helper: polar radar scans of a synthetic world of point reflectors seen from a moving
// sensor, with every azimuth fired from where the sensor is at that azimuth's time (so the
// scans carry the real motion distortion of a spinning radar).
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::test {

struct Reflector {
  double x, y, power;
};

/// Random reflectors in [xmin, xmax] x [ymin, ymax] plus straight "walls" of closely spaced ones.
inline std::vector<Reflector> makeWorld(unsigned seed, double xmin, double xmax, double ymin, double ymax,
                                        int points = 1500) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(xmin, xmax), uy(ymin, ymax), up(120, 255);
  std::vector<Reflector> w;
  for (int i = 0; i < points; ++i) w.push_back({ux(rng), uy(rng), up(rng)});
  std::uniform_real_distribution<double> ang(0, std::numbers::pi), len(5, 25);
  for (int k = 0; k < points / 20; ++k) {
    const double x0 = ux(rng), y0 = uy(rng), a = ang(rng), l = len(rng), p = up(rng) * 0.6;
    for (double s = 0; s < l; s += 0.6) w.push_back({x0 + s * std::cos(a), y0 + s * std::sin(a), p});
  }
  return w;
}

/// Sensor pose as a function of time (seconds): constant body velocity (vx, wz) from the origin.
struct ConstantTwistMotion {
  double vx = 10.0, vy = 0.0, wz = 0.05;
  void poseAt(double t, double& x, double& y, double& th) const {
    th = wz * t;
    if (std::abs(wz) < 1e-12) {
      x = vx * t;
      y = vy * t;
      return;
    }
    const double a = std::sin(th) / wz, b = (1 - std::cos(th)) / wz;
    x = a * vx - b * vy;
    y = b * vx + a * vy;
  }
};

struct SynthScanParams {
  std::uint32_t azimuths = 400;
  std::uint32_t bins = 2000;
  double resolution_m = 0.0432 * 2;
  double period_s = 0.25;
  double beam_sigma_rad = 0.9 * std::numbers::pi / 180 * 0.6;
  double range_sigma_m = 0.15;
  double noise = 12.0;  ///< speckle amplitude
  /// FMCW Doppler range offset (radar/doppler_compensation.h): a reflector appears s * beta * u
  /// nearer, u = the sensor's body velocity along the beam; s = +1, or -1 on odd azimuths when
  /// the chirp alternates (RAS6; the scan then carries azimuth_chirp). 0 = none.
  double doppler_beta_s = 0.0;
  bool alternating_chirp = false;
  StampNs t0_ns = 1'600'000'000'000'000'000LL;
};

/// Scan k fires azimuth i at t = k * period + i * period / azimuths (seconds from t0).
template <typename Motion>
CObservationRadarScan::Ptr renderScan(const std::vector<Reflector>& world, const Motion& motion, int k,
                                      const SynthScanParams& p, unsigned seed = 1) {
  auto scan = CObservationRadarScan::Create();
  scan->resize(p.azimuths, p.bins);
  scan->range_resolution_m = p.resolution_m;
  scan->range_offset_m = p.resolution_m / 2;
  std::mt19937 rng(seed * 7919u + static_cast<unsigned>(k));
  std::uniform_real_distribution<double> noise(0, p.noise);
  std::vector<float> row(p.bins);
  const double max_r = scan->maxRange();
  for (std::uint32_t i = 0; i < p.azimuths; ++i) {
    const double t = k * p.period_s + i * p.period_s / p.azimuths;
    scan->azimuth_stamps_ns[i] = p.t0_ns + static_cast<StampNs>(std::llround(t * 1e9));
    const double az = scan->azimuth_angles_rad[i];
    const int chirp = p.alternating_chirp && i % 2 ? -1 : 1;
    if (p.alternating_chirp) scan->azimuth_chirp[i] = static_cast<std::int8_t>(chirp);
    const double doppler = chirp * p.doppler_beta_s * (motion.vx * std::cos(az) + motion.vy * std::sin(az));
    double sx, sy, sth;
    motion.poseAt(t, sx, sy, sth);
    const double c = std::cos(sth), s = std::sin(sth);
    for (std::uint32_t b = 0; b < p.bins; ++b) row[b] = static_cast<float>(noise(rng));
    for (const auto& r : world) {
      const double dx = r.x - sx, dy = r.y - sy;
      const double lx = c * dx + s * dy, ly = -s * dx + c * dy;
      const double range = std::hypot(lx, ly);
      if (range > max_r || range < 1.0) continue;
      const double da = std::remainder(std::atan2(ly, lx) - az, 2 * std::numbers::pi);
      if (std::abs(da) > 3 * p.beam_sigma_rad) continue;
      const double ga = std::exp(-0.5 * da * da / (p.beam_sigma_rad * p.beam_sigma_rad));
      const double centre = (range - doppler - scan->range_offset_m) / p.resolution_m;
      const int spread = static_cast<int>(std::ceil(3 * p.range_sigma_m / p.resolution_m));
      for (int b = static_cast<int>(centre) - spread; b <= static_cast<int>(centre) + spread + 1; ++b) {
        if (b < 0 || b >= static_cast<int>(p.bins)) continue;
        const double d = (b - centre) * p.resolution_m;
        row[b] +=
            static_cast<float>(r.power * ga * std::exp(-0.5 * d * d / (p.range_sigma_m * p.range_sigma_m)));
      }
    }
    auto out = scan->row(i);
    for (std::uint32_t b = 0; b < p.bins; ++b) out[b] = static_cast<std::uint8_t>(std::min(255.f, row[b]));
  }
  scan->updateReferenceTime();
  return scan;
}

}  // namespace radarslam::test
