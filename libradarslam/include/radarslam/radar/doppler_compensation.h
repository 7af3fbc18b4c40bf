#pragma once
// Doppler range offset of an FMCW spinning radar (not in the RadarSLAM paper; Burnett et al.,
// "Do We Need to Compensate for Motion Distortion and Doppler Effects in Spinning Radar
// Navigation?", RA-L 2021, eq. (Doppler); yeti_radar_odometry).
//
// An FMCW radar measures range from the beat frequency between the transmitted and received
// chirps. A target closing at radial speed u adds a Doppler shift to that beat frequency, which
// the range FFT cannot tell from range: the return appears displaced along its beam by
//   r_measured = r_true - s * beta * u,      u = v_x cos(phi) + v_y sin(phi),
// where (v_x, v_y) is the sensor's velocity in its own frame (BodyVelocity), phi the azimuth
// angle, beta = f_c / (df/dt) [s] the sensor's ratio of carrier frequency to chirp slope, and
// s = +1 for an up-chirp, -1 for a down-chirp (the Doppler term changes sign with the slope).
// For static targets u is the sensor's own velocity along the beam: driving forward, what lies
// ahead appears closer by beta * v (up-chirp), what lies behind farther.
//
//  - Single-chirp sensors (CTS350-X, CIR204-H) have s = +1 on every azimuth: the offset is a
//    smooth, velocity-dependent distortion of the whole scan (Burnett et al.: beta = 0.049 s,
//    ~0.5 m ahead at 10 m/s).
//  - The RAS6 (Boreas-RT) alternates up and down chirps between consecutive azimuths
//    (CObservationRadarScan::azimuth_chirp = +1 / -1): neighbouring azimuths are shifted in
//    opposite directions, so a wall ahead becomes a comb +-beta * v wide.
//
// compensateDoppler() removes the offset: r_true = r_measured + s * beta * u, with s = +1 for
// azimuths whose chirp is unknown (0). The ego velocity comes from the tracker (the previous scan
// pair's twist); moving targets keep the offset of their own radial speed (not modelled).
#include <span>

#include "radarslam/obs/CObservationRadarScan.h"
#include "radarslam/radar/motion_compensation.h"
#include "radarslam/radar/peak_cloud.h"

namespace radarslam {

class YamlParams;

struct DopplerParams {
  // Off by default: only sensors whose beta is known may enable it in config/<sensor>.yaml.
  bool enabled = false;  ///< remove the Doppler range offset with the tracked ego velocity
  /// beta_s: beta = f_c / (df/dt); negative flips the chirp convention (flag 255 = down-chirp).
  double beta_s = 0.049;  ///< range offset per m/s of radial speed, s (CTS350-X 0.049); valid [-1, 1]
};

/// Overrides `params` from the keys enabled, beta_s of `yaml` (odometry: doppler: in the
/// sensor configs). Throws InputError for values out of range.
void loadParams(const YamlParams& yaml, DopplerParams& params);

/// The chirp sign used for an azimuth: its own direction, or +1 when unknown / single chirp.
inline int chirpSign(const CObservationRadarScan& scan, std::size_t azimuth) {
  return scan.chirp(azimuth) < 0 ? -1 : 1;
}

/// Doppler range offset s * beta * u [m] of a static target at azimuth angle `phi` seen with chirp
/// sign `s` from a sensor moving with `v`: how much SHORTER than the true range it is measured.
double dopplerRangeOffset(double beta_s, int s, const BodyVelocity& v, double phi);

/// Removes the Doppler offset from a polar scan in place: each azimuth row is resampled (linear
/// interpolation along range) so that bin k again holds the return from range binRange(k).
/// Bins whose source lies outside the row become 0. Cost: one pass over the image.
/// No-op when beta_s is 0 or the velocity is zero.
void compensateDoppler(CObservationRadarScan& scan, const BodyVelocity& v, double beta_s);

/// Removes the Doppler offset from points of `scan` (each along its own azimuth's angle and chirp):
/// range_m, x and y are moved out by the offset. Use on points still on their beam (before
/// compensateMotion). Throws InputError if a point's azimuth index is not in the scan.
void compensateDoppler(std::span<RadarPoint> points, const CObservationRadarScan& scan, const BodyVelocity& v,
                       double beta_s);

}  // namespace radarslam
