#include "radarslam/sim/radar_model.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <numbers>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/sim/rng.h"

namespace radarslam::sim {

StampNs RadarGeometry::scanPeriodNs() const { return static_cast<StampNs>(std::llround(1e9 / rotation_hz)); }

int RadarGeometry::encoder(int i) const {
  return static_cast<int>((static_cast<std::int64_t>(i + 1) * encoder_size) / azimuths - 1);
}

double RadarGeometry::angle(int i) const { return 2.0 * std::numbers::pi * encoder(i) / encoder_size; }

int RadarGeometry::chirpSign(int i) const { return chirp == "alternating" && i % 2 ? -1 : 1; }

Weather weatherPreset(const std::string& name) {
  Weather w;
  w.name = name;
  if (name == "clear") return w;
  if (name == "fog") {  // fog barely attenuates 77 GHz; droplets raise the floor a little
    w.noise_floor_gain_db = 3.0;
    w.attenuation_db_per_m = 0.004;  // ~1 g/m^3 of liquid water (ITU-R P.840), two-way: dense fog
    // No volume clutter: fog droplets (~20 um) scatter in the Rayleigh regime, ~-20 dBZ against
    // ~+40 dBZ of heavy rain, i.e. 60 dB below the rain preset's clutter; real RADIATE fog scans
    // show no near-range disc (docs/simulator.md, weather against real fog).
    return w;
  }
  if (name == "rain") {  // heavy rain: ~10 dB/km one-way, strong near-range backscatter
    w.noise_floor_gain_db = 4.5;
    w.attenuation_db_per_m = 0.02;
    w.volume_clutter_power = 150;
    w.volume_clutter_range_m = 35;
    return w;
  }
  if (name == "snow") {  // snow on the radome: the front half lost (paper Sec. V, Snow sequence)
    w.noise_floor_gain_db = 2.0;
    w.attenuation_db_per_m = 0.01;
    w.volume_clutter_power = 60;
    w.blanked_sector_deg = 180;
    w.blanked_centre_deg = 0;
    return w;
  }
  throw InputError("--weather", "unknown weather '" + name + "' (expected clear, fog, rain or snow)");
}

void loadGeometry(const YamlParams& y, RadarGeometry& g) {
  y.get("azimuths", g.azimuths, Range::closed(16, 4096));
  y.get("bins", g.bins, Range::closed(16, 16384));
  y.get("range_resolution_m", g.range_resolution_m, Range::closed(0.001, 10));
  y.get("rotation_hz", g.rotation_hz, Range::closed(0.1, 100));
  y.get("encoder_size", g.encoder_size, Range::closed(16, 1000000.0));
  y.get("doppler_beta_s", g.doppler_beta_s, Range::closed(-1, 1));
  y.get("chirp", g.chirp);
  if (g.chirp != "single" && g.chirp != "alternating")
    y.fail("chirp", "must be 'single' or 'alternating', not '" + g.chirp + "'");
}

void loadPhysics(const YamlParams& y, RadarPhysics& p) {
  y.get("beam_width_deg", p.beam_width_deg, Range::above(0, 90));
  y.get("rays_per_azimuth", p.rays_per_azimuth, Range::closed(1, 64));
  y.get("sidelobe_db", p.sidelobe_db, Range::closed(-200, 0));
  y.get("sidelobe_extent_deg", p.sidelobe_extent_deg, Range::closed(0, 180));
  y.get("power_scale", p.power_scale, Range::above(0, 1e+20));
  y.get("range_exponent", p.range_exponent, Range::closed(0, 10));
  y.get("specular_exponent", p.specular_exponent, Range::closed(0, 1000));
  y.get("range_psf_bins", p.range_psf_bins, Range::closed(0, 100));
  y.get("speckle_range_corr", p.speckle_range_corr, Range::closed(0, 0.999));
  y.get("speckle_azimuth_corr", p.speckle_azimuth_corr, Range::closed(0, 0.999));
  y.get("noise_floor_power", p.noise_floor_power, Range::closed(0, 1000000000000.0));
  y.get("near_noise_power", p.near_noise_power, Range::closed(0, 1000000000000.0));
  y.get("near_noise_range_m", p.near_noise_range_m, Range::above(0, 10000.0));
  y.get("azimuth_gain_jitter_db", p.azimuth_gain_jitter_db, Range::closed(0, 60));
  y.get("near_clutter_power", p.near_clutter_power, Range::closed(0, 1e+20));
  y.get("near_clutter_range_m", p.near_clutter_range_m, Range::closed(0, 1000));
  y.get("saturation_amplitude", p.saturation_amplitude, Range::above(0, 1e+20));
  y.get("streak_threshold_power", p.streak_threshold_power, Range::above(0, 1e+30));
  y.get("streak_power", p.streak_power, Range::closed(0, 1e+20));
  y.get("streak_probability", p.streak_probability, Range::closed(0, 1));
  y.get("streak_excess_min_db", p.streak_excess_min_db, Range::closed(0, 100));
  y.get("streak_excess_scale_db", p.streak_excess_scale_db, Range::closed(0, 100));
  y.get("multipath_db", p.multipath_db, Range::closed(-200, 0));
  y.get("multipath_min_cos", p.multipath_min_cos, Range::closed(0, 1));
  y.get("ground_clutter_power", p.ground_clutter_power, Range::closed(0, 1e+20));
  y.get("ground_clutter_exponent", p.ground_clutter_exponent, Range::closed(0, 10));
  y.get("ground_texture_m", p.ground_texture_m, Range::above(0, 1000));
  y.get("ground_beyond_wall", p.ground_beyond_wall, Range::closed(0, 1));
  y.get("ground_texture_peak", p.ground_texture_peak, Range::closed(0, 1e+6));
  y.get("ground_texture_power", p.ground_texture_power, Range::closed(0, 100));
  y.get("elevation_beam_width_deg", p.elevation_beam_width_deg, Range::closed(0, 90));
  y.get("mount_height_m", p.mount_height_m, Range::above(0, 100));
  y.get("stc_range_m", p.stc_range_m, Range::above(0, 1000));
  y.get("stc_exponent", p.stc_exponent, Range::closed(0, 40));
  y.get("code_per_octave", p.code_per_octave, Range::above(0, 100));
}

namespace {
double dbToLinear(double db) { return std::pow(10.0, db / 10.0); }

/// Navtech-like 8-bit code of an amplitude: the integer amplitude's log2 taken the way integer
/// hardware does (exponent + linear mantissa), times ~6.02 (= 20*log10(2)): 1 -> 0, 2 -> 6,
/// 3 -> 9, 4 -> 12, 5 -> 14, 6 -> 15, ... as in the real Oxford PNGs.
inline std::uint8_t amplitudeCode(float amplitude, float code_per_octave) {
  // Branch-free so that the per-bin loop vectorises; truncation = floor for amplitude >= 0.
  const int ai = static_cast<int>(amplitude);
  const std::uint32_t u = std::bit_cast<std::uint32_t>(static_cast<float>(ai > 1 ? ai : 1));
  const float log2a =
      static_cast<float>(static_cast<int>(u >> 23) - 127) + static_cast<float>(u & 0x7FFFFF) * 0x1.0p-23f;
  const int code = static_cast<int>(code_per_octave * log2a + 0.5f);
  return static_cast<std::uint8_t>(ai > 1 ? (code < 255 ? code : 255) : 0);
}

/// Range response of a target with depth: Gaussian PSF convolved with a finite depth profile,
/// normalised to a peak of 1. Index 0 is `pre` bins before the target's bin.
struct RangeKernel {
  int pre = 0;
  std::vector<float> w;
};

RangeKernel makeKernel(double sigma_bins, double depth_bins) {
  // Gaussian range response (window main lobe) convolved with a finite depth profile that decays
  // quadratically to zero over depth_bins (a wall's interior, a canopy's extent).
  RangeKernel k;
  k.pre = static_cast<int>(std::ceil(6 * sigma_bins));
  const int tail = static_cast<int>(std::ceil(depth_bins));
  const int post = k.pre + tail;
  k.w.resize(static_cast<std::size_t>(k.pre + post + 1));
  for (int j = -k.pre; j <= post; ++j) {
    double v = 0;
    for (int m = 0; m <= tail; ++m) {
      const double x = j - m;
      const double profile =
          tail > 0 ? (1.0 - static_cast<double>(m) / (tail + 1)) * (1.0 - static_cast<double>(m) / (tail + 1))
                   : 1.0;
      v += std::exp(-0.5 * x * x / (sigma_bins * sigma_bins)) * profile;
    }
    k.w[static_cast<std::size_t>(j + k.pre)] = static_cast<float>(v);
  }
  const float peak = *std::max_element(k.w.begin(), k.w.end());
  for (float& v : k.w) v /= peak;
  return k;
}
}  // namespace

struct RadarRenderer::Impl {
  const World& world;
  const Route& route;
  RadarGeometry g;
  RadarPhysics p;
  Weather weather;
  std::uint64_t seed;
  RayCaster caster, ghost_caster;
  std::vector<RayHit> hits, ghost_hits;
  std::vector<Segment> dynamic;
  std::vector<float> signal;        // azimuths x bins, linear power
  std::vector<float> floor_power;   // per bin
  std::vector<float> near_clutter;  // per bin: housing/mount returns + weather volume clutter
  std::vector<float> stc;           // per bin: sensitivity time control gain on echoes
  std::vector<float> max_direct;    // per azimuth, strongest direct return
  std::vector<int> chirp_sign;      // per azimuth, RadarGeometry::chirpSign
  std::vector<float> ground;        // azimuths x (bins / kGroundStep), ground clutter power
  static constexpr int kGroundStep = 16;
  std::vector<float> lobe;  // main-lobe gain at offsets (k / kLobeSteps) azimuths
  int lobe_half = 0;        // main lobe reaches +-lobe_half azimuths
  double sidelobe = 0;
  std::map<int, RangeKernel> kernels;  // by depth in centimetres
  std::vector<float> zr_prev, zi_prev, zr_cur, zi_cur, n1, n2;
  static constexpr int kLobeSteps = 32;

  Impl(const World& w, const Route& r, const RadarGeometry& geo, const RadarPhysics& phys, const Weather& wea,
       std::uint64_t s)
      : world(w), route(r), g(geo), p(phys), weather(wea), seed(s), caster(w), ghost_caster(w) {
    if (g.azimuths < 8 || g.bins < 16 || !(g.range_resolution_m > 0) || !(g.rotation_hz > 0) ||
        p.rays_per_azimuth < 1)
      throw InputError("radar geometry", "needs >= 8 azimuths, >= 16 bins, resolution > 0, rotation > 0");
    const std::size_t B = static_cast<std::size_t>(g.bins);
    signal.resize(static_cast<std::size_t>(g.azimuths) * B);
    floor_power.resize(B);
    near_clutter.resize(B);
    stc.resize(B);
    max_direct.resize(static_cast<std::size_t>(g.azimuths));
    for (int a = 0; a < g.azimuths; ++a) chirp_sign.push_back(g.chirpSign(a));
    ground.resize(static_cast<std::size_t>(g.azimuths) * (B / kGroundStep + 1));
    const double floor_gain = dbToLinear(weather.noise_floor_gain_db);
    for (std::size_t b = 0; b < B; ++b) {
      const double range = (static_cast<double>(b) + 0.5) * g.range_resolution_m;
      floor_power[b] = static_cast<float>(
          (p.noise_floor_power + p.near_noise_power * std::exp(-range / p.near_noise_range_m)) * floor_gain);
      const double q = range / p.near_clutter_range_m;
      near_clutter[b] = static_cast<float>(
          p.near_clutter_power * (std::exp(-q * q * q * q) + 0.01 * std::exp(-q)) +
          weather.volume_clutter_power * std::exp(-range / weather.volume_clutter_range_m));
      stc[b] =
          static_cast<float>(range < p.stc_range_m ? std::pow(range / p.stc_range_m, p.stc_exponent) : 1.0);
    }
    // Main lobe: Gaussian with the given two-way 3 dB width, in units of the azimuth step.
    const double step_deg = 360.0 / g.azimuths;
    const double sigma = p.beam_width_deg / step_deg / (2 * std::sqrt(2 * std::log(2.0)));
    // Two-way antenna pattern: Gaussian main lobe, then far sidelobes decaying from sidelobe_db
    // to ~15 dB lower at sidelobe_extent_deg.
    sidelobe = dbToLinear(p.sidelobe_db);
    lobe_half =
        std::max(1, static_cast<int>(std::ceil(std::max(p.sidelobe_extent_deg / step_deg, 3.5 * sigma))));
    lobe.resize(static_cast<std::size_t>((lobe_half + 1) * kLobeSteps + 1));
    for (std::size_t k = 0; k < lobe.size(); ++k) {
      const double x = static_cast<double>(k) / kLobeSteps;
      const double main = std::exp(-0.5 * x * x / (sigma * sigma));
      const double side = sidelobe * std::exp(-3.5 * x / lobe_half);
      lobe[k] = static_cast<float>(std::max(main, side));
    }
    zr_prev.resize(B), zi_prev.resize(B), zr_cur.resize(B), zi_cur.resize(B), n1.resize(B), n2.resize(B);
  }

  const RangeKernel& kernel(double depth_m) {
    const int cm = static_cast<int>(std::lround(depth_m * 100));
    auto it = kernels.find(cm);
    if (it == kernels.end())
      it = kernels.emplace(cm, makeKernel(p.range_psf_bins, cm * 0.01 / g.range_resolution_m)).first;
    return it->second;
  }

  float lobeGain(double offset) const {
    const double x = std::abs(offset) * kLobeSteps;
    const auto k = static_cast<std::size_t>(x);
    return k + 1 < lobe.size() ? lobe[k] : 0.0f;
  }

  void addRow(int az, int bin0, const RangeKernel& k, float power) {
    az %= g.azimuths;
    if (az < 0) az += g.azimuths;
    float* row = signal.data() + static_cast<std::size_t>(az) * g.bins;
    const int first = bin0 - k.pre;
    const int lo = std::max(0, first), hi = std::min(g.bins, first + static_cast<int>(k.w.size()));
    for (int b = lo; b < hi; ++b) row[b] += power * k.w[static_cast<std::size_t>(b - first)];
  }

  /// Spreads a return at fractional azimuth index `phi` over azimuths (antenna pattern) and bins.
  void splat(double phi, double range, float power, double depth_m) {
    const int bin0 = static_cast<int>(range / g.range_resolution_m);
    if (bin0 >= g.bins || power <= 0) return;
    const RangeKernel& k = kernel(depth_m);
    const int centre = static_cast<int>(std::lround(phi));
    const float faint = 0.05f * static_cast<float>(p.noise_floor_power);
    for (int da = -lobe_half; da <= lobe_half; ++da) {
      const float gain = lobeGain(centre + da - phi);
      if (power * gain > faint) addRow(centre + da, bin0, k, power * gain);
    }
  }

  float hitPower(const RayHit& h, double range, double through) const {
    const Surface& s = *h.surface;
    const double c = h.cos_incidence;
    const double law = (1.0 - s.roughness) * std::pow(c, p.specular_exponent) + s.roughness * c;
    const double atten = dbToLinear(-weather.attenuation_db_per_m * range);
    return static_cast<float>(p.power_scale * s.reflectivity * h.texture * law * through * atten /
                              std::pow(std::max(range, 1.0), p.range_exponent) / p.rays_per_azimuth);
  }

  /// Two-way elevation gain of the fan beam towards the ground at horizontal range r.
  double elevationGain(double r) const {
    if (!(p.elevation_beam_width_deg > 0)) return 1.0;
    const double psi = std::atan2(p.mount_height_m, r) * 180.0 / std::numbers::pi;
    const double sigma = p.elevation_beam_width_deg / (2 * std::sqrt(2 * std::log(2.0)));
    return std::exp(-0.5 * psi * psi / (sigma * sigma));
  }

  /// Ground returns of the vertical fan beam along azimuth a, up to the first wall; the texture
  /// is a hash of the world position, so the same patch of ground returns alike on every visit.
  void groundClutter(int a, Vec2 o, Vec2 d, double /*yaw*/) {
    double wall = g.maxRange();
    for (const RayHit& h : hits)
      if (h.surface->transmission < 0.1f) {
        wall = h.range;
        break;
      }
    const int cells = g.bins / kGroundStep + 1;
    float* row = ground.data() + static_cast<std::size_t>(a) * cells;
    const double step = kGroundStep * g.range_resolution_m;
    for (int c = 0; c < cells; ++c) {
      const double r = (c + 0.5) * step;
      const double beyond = r > wall ? p.ground_beyond_wall : 1.0;
      if (beyond <= 0) {
        row[c] = 0;
        continue;
      }
      const Vec2 q = o + d * r;
      const auto ix = static_cast<std::int64_t>(std::floor(q.x / p.ground_texture_m));
      const auto iy = static_cast<std::int64_t>(std::floor(q.y / p.ground_texture_m));
      const double h = hashToUnit(hashCombine(hashCombine(world.seed, static_cast<std::uint64_t>(ix)),
                                              static_cast<std::uint64_t>(iy)));
      const double tex = 0.02 + p.ground_texture_peak * std::pow(h, p.ground_texture_power);
      row[c] = static_cast<float>(p.ground_clutter_power * beyond * tex * elevationGain(r) *
                                  std::pow(std::max(r, 3.0) / 10.0, -p.ground_clutter_exponent) *
                                  dbToLinear(-weather.attenuation_db_per_m * r));
    }
  }

  /// FMCW Doppler: every return of a beam fired at `t` in direction `d` (world) appears
  /// s * beta * u nearer, u = the sensor's velocity along the beam (the returned offset; static
  /// world: movers get the sensor's speed too; ghosts the direct path's offset). Velocity by
  /// central difference of the route over +-5 ms.
  double dopplerOffset(StampNs t, int azimuth, const Vec2& d) const {
    constexpr StampNs h = 5'000'000;
    const auto p0 = route.poseAt(t - h), p1 = route.poseAt(t + h);
    const double u = ((p1.x - p0.x) * d.x + (p1.y - p0.y) * d.y) / toSeconds(2 * h);
    return chirp_sign[static_cast<std::size_t>(azimuth)] * g.doppler_beta_s * u;
  }

  void traceBeams(StampNs start, StampNs period) {
    std::fill(signal.begin(), signal.end(), 0.0f);
    std::fill(max_direct.begin(), max_direct.end(), 0.0f);
    const double max_range = g.maxRange();
    const auto mid = route.poseAt(start + period / 2);
    world.moverSegments(toSeconds(start + period / 2 - route.start_stamp), {mid.x, mid.y}, max_range + 10,
                        3.0, dynamic);
    const int J = p.rays_per_azimuth;
    const double step = 2 * std::numbers::pi / g.azimuths;
    for (int a = 0; a < g.azimuths; ++a) {
      for (int j = 0; j < J; ++j) {
        const double frac = (j + 0.5) / J - 0.5;  // sub-ray offset in azimuth steps
        const StampNs t = start + static_cast<StampNs>((a + frac) * static_cast<double>(period) / g.azimuths);
        const auto pose = route.poseAt(t);  // motion distortion: each firing from its own pose
        const double theta = pose.phi + g.angle(a) + frac * step;
        const Vec2 o{pose.x, pose.y}, d{std::cos(theta), std::sin(theta)};
        caster.cast(o, d, max_range, dynamic, hits);
        const double doppler = g.doppler_beta_s != 0.0 ? dopplerOffset(t, a, d) : 0.0;
        if (j == J / 2) groundClutter(a, o, d, pose.phi);
        double through = 1.0;
        for (const RayHit& h : hits) {
          const float power = hitPower(h, h.range, through);
          splat(a + frac, std::max(0.0, h.range - doppler), power, h.surface->depth_m);
          max_direct[static_cast<std::size_t>(a)] = std::max(max_direct[static_cast<std::size_t>(a)], power);
          // Multipath: a smooth wall seen near normal mirrors the beam; what it then hits
          // appears behind the wall at the total path length.
          if (j == J / 2 && h.surface->transmission < 0.1f && h.surface->roughness < 0.6f &&
              h.cos_incidence > p.multipath_min_cos) {
            const Vec2 q = o + d * h.range;
            const Vec2 m = d - h.normal * (2 * d.dot(h.normal));
            ghost_caster.cast(q + h.normal * 0.05, m, max_range - h.range, dynamic, ghost_hits);
            if (!ghost_hits.empty()) {
              const RayHit& gh = ghost_hits.front();
              const double total = h.range + gh.range;
              const float ghost = hitPower(gh, total, through) * J *
                                  static_cast<float>(dbToLinear(p.multipath_db)) *
                                  (1.0f - h.surface->roughness) * h.surface->reflectivity;
              splat(a + frac, std::max(0.0, total - doppler), ghost, gh.surface->depth_m);
            }
          }
          through *= h.surface->transmission;
        }
      }
    }
  }

  /// One streak's added power (RadarPhysics::streak_excess_min_db, streak_excess_scale_db).
  float streakPower(Rng& rng) const {
    if (p.streak_excess_scale_db <= 0) return static_cast<float>(p.streak_power);
    const double excess_db =
        p.streak_excess_min_db - p.streak_excess_scale_db * std::log(1.0 - rng.uniform());
    return static_cast<float>(std::min(p.streak_power, p.noise_floor_power * (dbToLinear(excess_db) - 1.0)));
  }

  void speckleAndQuantise(std::uint64_t scan_index, CObservationRadarScan& out) {
    Rng rng(hashCombine(hashCombine(seed, 0x5EC), scan_index));
    // Streak strengths from their own stream, so that they leave the speckle draws unchanged.
    Rng streak_rng(hashCombine(hashCombine(seed, 0x57EA), scan_index));
    const int A = g.azimuths, B = g.bins;
    const float alpha = static_cast<float>(p.speckle_range_corr),
                beta = static_cast<float>(p.speckle_azimuth_corr);
    const float innov = std::sqrt((1 - alpha * alpha) * (1 - beta * beta)) * std::sqrt(0.5f);
    const float innov_row = std::sqrt(1 - alpha * alpha) * std::sqrt(0.5f);
    const float innov_col = std::sqrt(1 - beta * beta) * std::sqrt(0.5f);
    const float sat = static_cast<float>(p.saturation_amplitude);
    const float cpo = static_cast<float>(p.code_per_octave);
    const auto& table = normalTable();
    const double blank_half = weather.blanked_sector_deg * std::numbers::pi / 360.0;
    const double blank_centre = weather.blanked_centre_deg * std::numbers::pi / 180.0;
    const float residual = static_cast<float>(dbToLinear(weather.blanked_residual_db));
    for (int a = 0; a < A; ++a) {
      float gain = static_cast<float>(dbToLinear(p.azimuth_gain_jitter_db * rng.normal()));
      float streak = 0;
      if (max_direct[static_cast<std::size_t>(a)] > p.streak_threshold_power &&
          rng.chance(p.streak_probability))
        streak = streakPower(streak_rng);
      float keep = 1.0f, keep_floor = 1.0f;
      if (blank_half > 0 &&
          std::abs(std::remainder(g.angle(a) - blank_centre, 2 * std::numbers::pi)) < blank_half)
        keep = residual, keep_floor = 0.25f, streak = 0;  // nothing strong gets through the snow
      const float* s = signal.data() + static_cast<std::size_t>(a) * B;
      const float* gr = ground.data() + static_cast<std::size_t>(a) * (B / kGroundStep + 1);
      std::uint8_t* px = out.power.data() + static_cast<std::size_t>(a) * B;
      // Split into passes so that all but the recursion itself vectorises.
      for (int b = 0; b < B; ++b) {  // white complex Gaussian innovations
        const std::uint64_t r = rng.next();
        n1[b] = table[r >> 52], n2[b] = table[(r >> 40) & 4095];
      }
      if (a == 0) {  // first row: AR(1) along range only
        float zr = n1[0] * std::sqrt(0.5f), zi = n2[0] * std::sqrt(0.5f);
        zr_cur[0] = zr, zi_cur[0] = zi;
        for (int b = 1; b < B; ++b) {
          zr = alpha * zr + innov_row * n1[b], zi = alpha * zi + innov_row * n2[b];
          zr_cur[b] = zr, zi_cur[b] = zi;
        }
      } else {  // separable 2D AR(1): correlation alpha^|db| * beta^|da|
        zr_cur[0] = beta * zr_prev[0] + innov_col * n1[0];
        zi_cur[0] = beta * zi_prev[0] + innov_col * n2[0];
        for (int b = 1; b < B; ++b) {
          n1[b] = beta * zr_prev[b] - alpha * beta * zr_prev[b - 1] + innov * n1[b];
          n2[b] = beta * zi_prev[b] - alpha * beta * zi_prev[b - 1] + innov * n2[b];
        }
        float zr = zr_cur[0], zi = zi_cur[0];
        for (int b = 1; b < B; ++b) {
          zr = alpha * zr + n1[b], zi = alpha * zi + n2[b];
          zr_cur[b] = zr, zi_cur[b] = zi;
        }
      }
      for (int b = 0; b < B; ++b) {
        const float mean = (((s[b] + gr[b / kGroundStep]) * stc[b] + near_clutter[b]) * keep +
                            (floor_power[b] + streak) * keep_floor) *
                           gain;
        const float amp = std::min(std::sqrt(mean * (zr_cur[b] * zr_cur[b] + zi_cur[b] * zi_cur[b])), sat);
        px[b] = amplitudeCode(amp, cpo);
      }
      std::swap(zr_prev, zr_cur);
      std::swap(zi_prev, zi_cur);
    }
  }
};

RadarRenderer::RadarRenderer(const World& world, const Route& route, const RadarGeometry& geometry,
                             const RadarPhysics& physics, const Weather& weather, std::uint64_t seed)
    : impl_(std::make_unique<Impl>(world, route, geometry, physics, weather, seed)), geometry_(geometry) {}

RadarRenderer::~RadarRenderer() = default;

StampNs RadarRenderer::azimuthStamp(StampNs start, int i) const {
  const StampNs offset = geometry_.scanPeriodNs() * i / geometry_.azimuths;
  return start + offset / kNsPerUs * kNsPerUs;  // whole microseconds, as Oxford files store
}

void RadarRenderer::render(StampNs start, std::uint64_t scan_index, CObservationRadarScan& out) {
  const RadarGeometry& g = geometry_;
  out.resize(static_cast<std::uint32_t>(g.azimuths), static_cast<std::uint32_t>(g.bins));
  out.range_resolution_m = g.range_resolution_m;
  out.range_offset_m = 0.5 * g.range_resolution_m;  // bin centres, as the Oxford SDK
  out.sensorLabel = "RADAR_SIM";
  for (int i = 0; i < g.azimuths; ++i) {
    out.azimuth_stamps_ns[static_cast<std::size_t>(i)] = azimuthStamp(start, i);
    out.azimuth_angles_rad[static_cast<std::size_t>(i)] = g.angle(i);
    if (g.chirp == "alternating")
      out.azimuth_chirp[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(g.chirpSign(i));
  }
  out.updateReferenceTime();
  impl_->traceBeams(start, g.scanPeriodNs());
  impl_->speckleAndQuantise(scan_index, out);
}

const std::array<float, 4096>& normalTable() {
  static const std::array<float, 4096> table = [] {
    std::array<float, 4096> t{};
    // Inverse normal CDF by bisection on erfc (built once).
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double q = (static_cast<double>(i) + 0.5) / t.size();
      double lo = -8, hi = 8;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < q ? lo : hi) = mid;
      }
      t[i] = static_cast<float>(0.5 * (lo + hi));
    }
    return t;
  }();
  return table;
}

}  // namespace radarslam::sim
