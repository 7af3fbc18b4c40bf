#pragma once
// The simulated radar: sensor geometry, the physics that make real Navtech data hard, and the
// weather presets. Rendering a scan:
//  1. every azimuth is fired from the radar pose at its own time (motion distortion); a beam is
//     traced as `rays_per_azimuth` sub-rays through the world (partial occlusion, multiple returns
//     through foliage/fences/cars);
//  2. each hit's power (reflectivity x texture x incidence law x range loss x weather
//     attenuation) is spread over neighbouring azimuths by the antenna pattern (Gaussian main lobe,
//     1.27 deg two-way 3 dB, plus far sidelobes for strong targets) and over range bins by the range
//     response and the target's depth; specular walls add multipath ghosts behind them;
//  3. echoes and ground clutter (lit by the fan beam's elevation pattern) pass the near-field
//     gain ramp (STC); noise floor (per-azimuth gain jitter), housing clutter, receiver
//     saturation streaks and weather clutter are added; the result is multiplied by a speckle
//     field (complex Gaussian, correlated along range and azimuth) and compressed to 8 bit the way
//     the Navtech does (about 20*log10 of an integer amplitude, in 1 dB-like steps).
#include <memory>
#include <string>

#include "radarslam/core/time.h"
#include "radarslam/obs/CObservationRadarScan.h"
#include "radarslam/sim/route.h"
#include "radarslam/sim/world.h"

namespace radarslam {
class YamlParams;
}

namespace radarslam::sim {

struct RadarGeometry {
  int azimuths = 400;                  ///< per rotation (Oxford CTS350-X: 400); valid [16, 4096]
  int bins = 3768;                     ///< range bins (Oxford: 3768); valid [16, 16384]
  double range_resolution_m = 0.0432;  ///< valid [0.001, 10]
  double rotation_hz = 4.0;            ///< 4 Hz = 240 rpm; valid [0.1, 100]
  int encoder_size = 5600;             ///< encoder counts per revolution (Navtech); valid [16, 1000000]
  // FMCW Doppler range offset (radar/doppler_compensation.h): a static target at radial closing
  // speed u appears s * beta * u nearer. chirp "single": every azimuth an up-chirp (s = +1;
  // CTS350-X, CIR204-H); "alternating": even azimuths up, odd down (RAS6; scans carry
  // azimuth_chirp and the writer puts the chirp flag into byte 10 of each row).
  double doppler_beta_s = 0.0;   ///< Doppler range offset per m/s radial speed, s; 0 = off; valid [-1, 1]
  std::string chirp = "single";  ///< single | alternating (up/down chirps on alternate azimuths)

  double maxRange() const { return bins * range_resolution_m; }
  StampNs scanPeriodNs() const;
  /// Encoder count of azimuth i (Oxford: 13, 27, ..., 5599).
  int encoder(int i) const;
  double angle(int i) const;  ///< radians, from the encoder count
  /// Chirp direction of azimuth i: +1 up, -1 down (chirp "alternating": odd azimuths).
  int chirpSign(int i) const;
};

struct RadarPhysics {
  double beam_width_deg =
      1.27;  ///< two-way 3 dB width of the main lobe (1.8 deg one-way / sqrt 2); valid (0, 90]
  int rays_per_azimuth = 4;         ///< sub-rays traced per azimuth; valid [1, 64]
  double sidelobe_db = -65;         ///< far sidelobe level relative to the main lobe; valid [-200, 0]
  double sidelobe_extent_deg = 10;  ///< far sidelobes reach this far either side; valid [0, 180]
  double power_scale = 2.4e10;      ///< received power of a unit target at 1 m; valid (0, 1e+20]
  double range_exponent = 0.4;      ///< power falls as range^-exponent; valid [0, 10]
  double specular_exponent = 20;    ///< sharpness of the specular lobe (smooth surfaces); valid [0, 1000]
  double range_psf_bins = 1.5;      ///< sigma of the range response, bins; valid [0, 100]
  double speckle_range_corr =
      0.93;  ///< correlation of the speckle field between adjacent bins; valid [0, 0.999]
  double speckle_azimuth_corr = 0.2;    ///< ... between adjacent azimuths; valid [0, 0.999]
  double noise_floor_power = 5.5;       ///< mean noise power (amplitude^2) far away; valid [0, 1000000000000]
  double near_noise_power = 0;          ///< extra noise power close to the radar; valid [0, 1000000000000]
  double near_noise_range_m = 60.0;     ///< e-folding range of the extra near noise; valid (0, 10000]
  double azimuth_gain_jitter_db = 1.5;  ///< per-azimuth receiver gain variation; valid [0, 60]
  double near_clutter_power = 3.0e3;    ///< housing/mount returns in the first metres; valid [0, 1e+20]
  double near_clutter_range_m = 1.6;    ///< valid [0, 1000]
  double saturation_amplitude = 6.0e6;  ///< receiver clips here (pixel ~136); valid (0, 1e+20]
  double streak_threshold_power = 1.5e8;  ///< a return this strong saturates the receiver; valid (0, 1e+30]
  double streak_power = 3.0e3;      ///< ...raising the whole azimuth by at most this power; valid [0, 1e+20]
  double streak_probability = 0.1;  ///< chance a saturating azimuth shows the streak; valid [0, 1]
  /// A streak's strength: its excess over the far noise floor (noise_floor_power) is
  /// streak_excess_min_db + an exponential draw of mean streak_excess_scale_db, capped at
  /// streak_power. Fitted to the real Oxford scans' streaks (docs/simulator.md, "Saturation
  /// streaks"): most are 6-10 codes (1 code ~ 1 dB), few reach 15. Scale 0 = every streak at
  /// streak_power (the model before 2026-12-07).
  double streak_excess_min_db = 6;     ///< valid [0, 100]
  double streak_excess_scale_db = 4;   ///< valid [0, 100]
  double multipath_db = -14;           ///< ghost power relative to the direct return; valid [-200, 0]
  double multipath_min_cos = 0.55;     ///< only near-normal specular walls make ghosts; valid [0, 1]
  double ground_clutter_power = 1200;  ///< road/grass returns of the fan beam at 10 m; valid [0, 1e+20]
  double ground_clutter_exponent =
      1.2;  ///< ...falling as range^-exponent, up to the first wall; valid [0, 10]
  /// Clutter the fan beam still sees beyond the first opaque wall (over low buildings: upper
  /// storeys, roofs, trees), as a fraction of the ground clutter there; valid [0, 1]
  double ground_beyond_wall = 0.1;
  double ground_texture_m = 0.7;  ///< ground patches (stable across scans); valid (0, 1000]
  /// Patch reflectivity 0.02 + ground_texture_peak * u^ground_texture_power (u uniform): most
  /// of the road is dark, a few patches (kerbs, drains, grass tufts) are bright scatterers.
  double ground_texture_peak = 6;   ///< valid [0, 1e+6]
  double ground_texture_power = 6;  ///< valid [0, 100]
  /// Elevation pattern of the fan beam: two-way gain exp(-0.5 (psi / sigma)^2) at depression
  /// angle psi = atan(mount_height / range), sigma = this full 3 dB width / 2.355 (pattern centred
  /// on the horizon, half power at psi = width / 2). The ground under the radar is outside the
  /// beam; with 2 m and 10 deg it reaches half power at ~23 m. 0 = off.
  double elevation_beam_width_deg = 10;  ///< valid [0, 90]
  double mount_height_m = 2.0;           ///< antenna height above the road; valid (0, 100]
  /// Sensitivity time control: the receiver gain rises as (range / stc_range_m)^stc_exponent up
  /// to stc_range_m (keeps the near field out of saturation); applies to echoes, not to the
  /// thermal noise floor or the housing returns. stc_exponent 0 = off.
  double stc_range_m = 11;        ///< valid (0, 1000]
  double stc_exponent = 20;       ///< valid [0, 40]
  double code_per_octave = 6.02;  ///< 8-bit code per doubling of amplitude (20*log10); valid (0, 100]
};

/// Weather effects on top of the physics.
struct Weather {
  std::string name = "clear";
  double noise_floor_gain_db = 0;   ///< raises the noise floor (rain/fog clutter)
  double attenuation_db_per_m = 0;  ///< two-way path attenuation
  double volume_clutter_power = 0;  ///< rain backscatter near the radar
  double volume_clutter_range_m = 30;
  double blanked_sector_deg = 0;     ///< snow on the radome: width of the lost sector...
  double blanked_centre_deg = 0;     ///< ...centred here (0 = straight ahead)
  double blanked_residual_db = -50;  ///< what is left of returns in the sector
};

/// "clear", "fog", "rain" or "snow". Throws InputError for anything else.
Weather weatherPreset(const std::string& name);

/// Overrides from a YAML section (keys = field names). Throws InputError for a chirp other than
/// single / alternating.
void loadGeometry(const YamlParams& yaml, RadarGeometry& g);
void loadPhysics(const YamlParams& yaml, RadarPhysics& p);

/// Renders scans of a world along a route. Not thread-safe (holds scratch buffers).
class RadarRenderer {
 public:
  RadarRenderer(const World& world, const Route& route, const RadarGeometry& geometry,
                const RadarPhysics& physics, const Weather& weather, std::uint64_t seed);
  ~RadarRenderer();

  /// Renders the scan whose first azimuth fires at `start` (stamps are whole microseconds, as
  /// Oxford files store them). `scan_index` seeds the noise, so rendering is reproducible.
  void render(StampNs start, std::uint64_t scan_index, CObservationRadarScan& out);

  /// Stamp of azimuth i of a scan starting at `start`.
  StampNs azimuthStamp(StampNs start, int i) const;

  const RadarGeometry& geometry() const { return geometry_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  RadarGeometry geometry_;
};

}  // namespace radarslam::sim
