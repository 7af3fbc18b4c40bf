#include "radarslam/sim/scan_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "range_bins.h"

namespace radarslam::sim {

ScanStatistics computeScanStatistics(const CObservationRadarScan& scan, const StatisticsParams& params) {
  ScanStatistics out;
  const std::size_t first_bin = detail::firstBinAtOrBeyond(scan, params.min_range_m);
  const std::size_t bins = scan.num_bins;
  if (first_bin >= bins || params.bands < 1) return out;
  const std::size_t per_band = (bins - first_bin) / static_cast<std::size_t>(params.bands);
  double total = 0, bright_total = 0;
  for (int k = 0; k < params.bands; ++k) {
    const std::size_t b0 = first_bin + k * per_band, b1 = k + 1 == params.bands ? bins : b0 + per_band;
    std::array<std::size_t, 256> h{};
    double sum = 0, sum2 = 0;
    for (std::size_t a = 0; a < scan.num_azimuths; ++a) {
      const auto row = scan.row(a);
      for (std::size_t b = b0; b < b1; ++b) {
        const unsigned v = row[b];
        ++h[v];
        sum += v;
        sum2 += static_cast<double>(v) * v;
      }
    }
    const double n = static_cast<double>((b1 - b0) * scan.num_azimuths);
    BandStatistics band;
    band.range_min_m = scan.binRange(b0), band.range_max_m = scan.binRange(b1);
    std::size_t acc = 0;
    int median = 0;
    for (; median < 256; ++median)
      if ((acc += h[static_cast<std::size_t>(median)]) * 2 >= n) break;
    band.floor = median;
    band.mean = sum / n;
    band.stddev = std::sqrt(std::max(0.0, sum2 / n - band.mean * band.mean));
    band.contrast = band.mean > 0 ? band.stddev / band.mean : 0;
    const int threshold = median + static_cast<int>(std::ceil(params.bright_margin_db));
    std::size_t bright = 0;
    for (int v = std::min(threshold, 256); v < 256; ++v) bright += h[static_cast<std::size_t>(v)];
    band.bright_fraction = static_cast<double>(bright) / n;
    for (std::size_t v = 0; v < 256; ++v) out.histogram[v] += static_cast<double>(h[v]);
    total += n;
    bright_total += static_cast<double>(bright);
    out.bands.push_back(band);
  }
  for (double& v : out.histogram) v /= total;
  out.bright_fraction = bright_total / total;
  out.zero_fraction = out.histogram[0];
  return out;
}

ScanStatistics averageStatistics(const std::vector<ScanStatistics>& stats) {
  ScanStatistics out;
  if (stats.empty()) return out;
  const double n = static_cast<double>(stats.size());
  out.bands.resize(stats.front().bands.size());
  for (const auto& s : stats) {
    for (std::size_t v = 0; v < 256; ++v) out.histogram[v] += s.histogram[v] / n;
    out.bright_fraction += s.bright_fraction / n;
    out.zero_fraction += s.zero_fraction / n;
    for (std::size_t k = 0; k < out.bands.size() && k < s.bands.size(); ++k) {
      auto& o = out.bands[k];
      const auto& b = s.bands[k];
      o.range_min_m = b.range_min_m, o.range_max_m = b.range_max_m;
      o.floor += b.floor / n, o.mean += b.mean / n, o.stddev += b.stddev / n;
      o.contrast += b.contrast / n, o.bright_fraction += b.bright_fraction / n;
    }
  }
  return out;
}

double histogramDistance(const std::array<double, 256>& a, const std::array<double, 256>& b) {
  double ca = 0, cb = 0, d = 0;
  for (std::size_t v = 0; v < 256; ++v) {
    ca += a[v], cb += b[v];
    d += std::abs(ca - cb);
  }
  return d;
}

std::string compareStatisticsTable(const ScanStatistics& real, const ScanStatistics& sim) {
  std::string out = "range band [m]   floor real/sim   contrast real/sim   bright real/sim\n";
  char line[160];
  for (std::size_t k = 0; k < real.bands.size() && k < sim.bands.size(); ++k) {
    const auto &r = real.bands[k], &s = sim.bands[k];
    std::snprintf(line, sizeof line, "%6.1f-%6.1f    %5.1f / %5.1f     %5.2f / %5.2f       %.3f / %.3f\n",
                  r.range_min_m, r.range_max_m, r.floor, s.floor, r.contrast, s.contrast, r.bright_fraction,
                  s.bright_fraction);
    out += line;
  }
  std::snprintf(line, sizeof line,
                "histogram distance (EMD) %.2f codes; zero fraction %.3f / %.3f; bright %.3f / %.3f\n",
                histogramDistance(real.histogram, sim.histogram), real.zero_fraction, sim.zero_fraction,
                real.bright_fraction, sim.bright_fraction);
  out += line;
  return out;
}

}  // namespace radarslam::sim
