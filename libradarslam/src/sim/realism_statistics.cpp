#include "radarslam/sim/realism_statistics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "range_bins.h"

namespace radarslam::sim {

const char* const kRealismNames[kRealismStatCount] = {
    "median code",         "zero fraction",    "bright fraction (>=60)", "99th percentile",
    "Alg.1 peaks /az/10m", "speckle contrast", "range corr. length [m]", "azimuth corr. length [deg]"};

std::vector<RealismBand> defaultRealismBands() { return {{2, 10}, {10, 40}, {40, 80}, {80, 160}}; }

namespace {

/// Lag (fractional) where the normalised autocovariance r(lag) = cov(lag) / cov(0) first drops
/// below 1/e; `cov(lag)` sums over all segments. Returns max_lag if it never does.
template <class Cov>
double correlationLength(Cov cov, int max_lag) {
  const double c0 = cov(0);
  if (!(c0 > 0)) return 0;
  const double target = std::exp(-1.0);
  double prev = 1.0;
  for (int lag = 1; lag <= max_lag; ++lag) {
    const double r = cov(lag) / c0;
    if (r < target) return lag - 1 + (prev - target) / (prev - r);
    prev = r;
  }
  return max_lag;
}

}  // namespace

RealismStatistics computeRealismStatistics(const CObservationRadarScan& scan, const RealismParams& params) {
  RealismStatistics out;
  const std::size_t A = scan.num_azimuths, B = scan.num_bins;
  if (A == 0 || B == 0) return out;
  const double res = scan.range_resolution_m;
  const auto points = extractPeakCloud(scan, params.peaks);
  std::vector<double> centred;
  for (const RealismBand& band : params.bands) {
    RealismBandStats st;
    st.band = band;
    const std::size_t b0 = detail::firstBinAtOrBeyond(scan, band.min_m);
    const std::size_t b1 = detail::firstBinAtOrBeyond(scan, band.max_m);
    if (b1 <= b0 + 2) {
      out.bands.push_back(st);
      continue;
    }
    const std::size_t W = b1 - b0;
    std::array<std::size_t, 256> h{};
    double sum = 0, sum2 = 0;
    for (std::size_t a = 0; a < A; ++a) {
      const auto row = scan.row(a);
      for (std::size_t b = b0; b < b1; ++b) {
        const unsigned v = row[b];
        ++h[v];
        sum += v, sum2 += static_cast<double>(v) * v;
      }
    }
    const double n = static_cast<double>(W * A);
    const auto quantile = [&](double q) {
      std::size_t acc = 0;
      for (int v = 0; v < 256; ++v)
        if (static_cast<double>(acc += h[static_cast<std::size_t>(v)]) >= q * n)
          return static_cast<double>(v);
      return 255.0;
    };
    const double mean = sum / n;
    std::size_t bright = 0;
    for (int v = std::clamp(params.bright_code, 0, 256); v < 256; ++v)
      bright += h[static_cast<std::size_t>(v)];
    st.value[kMedian] = quantile(0.5);
    st.value[kZeroFraction] = static_cast<double>(h[0]) / n;
    st.value[kBrightFraction] = static_cast<double>(bright) / n;
    st.value[kP99] = quantile(0.99);
    st.value[kContrast] = mean > 0 ? std::sqrt(std::max(0.0, sum2 / n - mean * mean)) / mean : 0;
    // Algorithm-1 points whose range falls in the band, per azimuth per 10 m of the band.
    const double r0 = scan.binRange(b0), r1 = scan.binRange(b1);
    std::size_t peaks = 0;
    for (const RadarPoint& p : points)
      if (p.range_m >= r0 && p.range_m < r1) ++peaks;
    st.value[kPeakDensity] = static_cast<double>(peaks) / static_cast<double>(A) / ((r1 - r0) / 10.0);
    // Range correlation: each azimuth's band segment with its own mean removed.
    centred.assign(W * A, 0.0);
    for (std::size_t a = 0; a < A; ++a) {
      const auto row = scan.row(a);
      double m = 0;
      for (std::size_t b = b0; b < b1; ++b) m += row[b];
      m /= static_cast<double>(W);
      for (std::size_t b = b0; b < b1; ++b) centred[a * W + (b - b0)] = row[b] - m;
    }
    const int max_rlag = std::min<int>(params.max_range_lag, static_cast<int>(W) - 1);
    const double rlag = correlationLength(
        [&](int lag) {
          double c = 0;
          for (std::size_t a = 0; a < A; ++a) {
            const double* x = centred.data() + a * W;
            for (std::size_t i = 0; i + static_cast<std::size_t>(lag) < W; ++i) c += x[i] * x[i + lag];
          }
          return c / static_cast<double>(W - static_cast<std::size_t>(lag));
        },
        max_rlag);
    st.value[kRangeCorrM] = rlag * res;
    // Azimuth correlation: each bin's column (circular in azimuth) with its own mean removed.
    std::vector<double> col_mean(W, 0.0);
    for (std::size_t a = 0; a < A; ++a)
      for (std::size_t i = 0; i < W; ++i) col_mean[i] += centred[a * W + i];
    for (double& m : col_mean) m /= static_cast<double>(A);
    for (std::size_t a = 0; a < A; ++a)
      for (std::size_t i = 0; i < W; ++i) centred[a * W + i] -= col_mean[i];
    const int max_alag = std::min<int>(params.max_azimuth_lag, static_cast<int>(A) / 2);
    const double alag = correlationLength(
        [&](int lag) {
          double c = 0;
          for (std::size_t a = 0; a < A; ++a) {
            const double* x = centred.data() + a * W;
            const double* y = centred.data() + ((a + static_cast<std::size_t>(lag)) % A) * W;
            for (std::size_t i = 0; i < W; ++i) c += x[i] * y[i];
          }
          return c;
        },
        max_alag);
    st.value[kAzimuthCorrDeg] = alag * 360.0 / static_cast<double>(A);
    out.bands.push_back(st);
  }
  return out;
}

RealismStatistics averageRealism(const std::vector<RealismStatistics>& stats) {
  RealismStatistics out;
  if (stats.empty()) return out;
  out.bands = stats.front().bands;
  for (auto& b : out.bands) std::fill(std::begin(b.value), std::end(b.value), 0.0);
  const double n = static_cast<double>(stats.size());
  for (const auto& s : stats)
    for (std::size_t k = 0; k < out.bands.size() && k < s.bands.size(); ++k)
      for (int i = 0; i < kRealismStatCount; ++i) out.bands[k].value[i] += s.bands[k].value[i] / n;
  return out;
}

double realismAbsoluteFloor(RealismStat stat) {
  switch (stat) {
    case kMedian:
    case kP99:
      return 1.0;  // one code (~1 dB)
    case kZeroFraction:
    case kBrightFraction:
      return 0.001;  // 0.1 % of the band's bins
    case kPeakDensity:
      return 0.01;
    case kContrast:
      return 0.02;
    case kRangeCorrM:
      return 0.02;  // half an Oxford bin
    case kAzimuthCorrDeg:
      return 0.45;  // half an Oxford azimuth step
    default:
      return 0;
  }
}

bool realismWithin(RealismStat stat, double real, double sim, double factor) {
  if (std::abs(real - sim) <= realismAbsoluteFloor(stat)) return true;
  if (real <= 0 || sim <= 0) return false;
  return sim <= real * factor && real <= sim * factor;
}

RealismComparison compareRealism(const RealismStatistics& real, const RealismStatistics& sim, double factor) {
  RealismComparison out;
  char line[200];
  std::snprintf(line, sizeof line, "%-9s %-27s %9s %9s %7s  within x%.1f?\n", "band [m]", "statistic", "real",
                "sim", "ratio", factor);
  out.table = line;
  for (std::size_t k = 0; k < real.bands.size() && k < sim.bands.size(); ++k) {
    const auto &r = real.bands[k], &s = sim.bands[k];
    char band[32];
    std::snprintf(band, sizeof band, "%.0f-%.0f", r.band.min_m, r.band.max_m);
    for (int i = 0; i < kRealismStatCount; ++i) {
      const auto stat = static_cast<RealismStat>(i);
      const bool ok = realismWithin(stat, r.value[i], s.value[i], factor);
      ++out.checked;
      out.within += ok ? 1 : 0;
      char ratio[16] = "  -";
      if (r.value[i] > 0) std::snprintf(ratio, sizeof ratio, "%.2f", s.value[i] / r.value[i]);
      std::snprintf(line, sizeof line, "%-9s %-27s %9.4g %9.4g %7s  %s\n", band, kRealismNames[i], r.value[i],
                    s.value[i], ratio, ok ? "yes" : "NO");
      out.table += line;
    }
  }
  std::snprintf(line, sizeof line, "%d of %d statistics within x%.1f (%.0f %%)\n", out.within, out.checked,
                factor, out.checked ? 100.0 * out.within / out.checked : 0.0);
  out.table += line;
  return out;
}

}  // namespace radarslam::sim
