#include "radarslam/radar/find_peaks.h"

#include <algorithm>
#include <numeric>

namespace radarslam {

namespace {

// The signal reduced to its turning points: every local-maximum run, every local-minimum run and
// the first and last runs (a run = consecutive equal samples). Prominence only depends on these:
// a base is a minimum of the signal, reached at a local minimum or an end, and the nearest
// strictly higher sample on a side lies on an ascent whose top is a local maximum or an end that
// is higher still. Speckled radar rows have ~10x fewer turning points than samples.
struct Extremum {
  float value;
  std::uint32_t first, last;  // sample range of the run
  bool is_peak;               // local-maximum run that is not at an end of the signal
};

// Per-thread scratch buffers: findPeaks runs once per azimuth, 400 times per scan.
struct Scratch {
  std::vector<Extremum> ext;
  std::vector<float> base_left, base_right;
  std::vector<std::pair<float, float>> stack;  // (value, min since the entry below)
  std::vector<std::uint32_t> priority;
  std::vector<char> removed;
  std::vector<std::uint32_t> change_at;  // turningPoints: sample indices i with x[i] != x[i - 1]
  std::vector<std::uint8_t> change_up;   // and whether x rose there
};

// Two branch-free passes (speckle makes every comparison a coin flip for a branch predictor):
// first the sample indices where the value changes, with the direction of the change; then a
// turning point wherever the direction differs from the previous change's.
template <typename T>
void turningPoints(std::span<const T> x, Scratch& s) {
  std::vector<Extremum>& ext = s.ext;
  const auto n = static_cast<std::uint32_t>(x.size());
  s.change_at.resize(n);
  s.change_up.resize(n);
  std::uint32_t k = 0;
  for (std::uint32_t i = 1; i < n; ++i) {
    s.change_at[k] = i;
    s.change_up[k] = x[i] > x[i - 1];
    k += x[i] != x[i - 1];
  }
  ext.clear();
  if (k == 0) {  // constant signal: a single run
    ext.push_back({static_cast<float>(x[0]), 0, n - 1, false});
    return;
  }
  // A run ends just before each change; it is a turning point when the direction flips there.
  ext.resize(k + 1);
  ext[0] = {static_cast<float>(x[0]), 0, s.change_at[0] - 1, false};  // first run: never a peak
  std::size_t m = 1;
  for (std::uint32_t j = 1; j < k; ++j) {
    const std::uint32_t i = s.change_at[j];
    ext[m] = {static_cast<float>(x[i - 1]), s.change_at[j - 1], i - 1, s.change_up[j - 1] != 0};
    m += s.change_up[j] != s.change_up[j - 1];  // up then down: local max; down then up: min
  }
  ext[m++] = {static_cast<float>(x[n - 1]), s.change_at[k - 1], n - 1, false};  // last run
  ext.resize(m);
}

// base[e] = min of the values over (g, e], g = the nearest element before e that is strictly
// higher than e (or the start): one monotonic-stack pass. Entries hold strictly decreasing
// values; each keeps the minimum since the entry below it, so popping merges covered spans.
template <typename It>
void bases(It begin, It end, std::vector<std::pair<float, float>>& stack, float* base, int step) {
  stack.clear();
  for (It it = begin; it != end; ++it, base += step) {
    float m = it->value;
    while (!stack.empty() && stack.back().first <= it->value) {
      m = std::min(m, stack.back().second);
      stack.pop_back();
    }
    *base = m;
    stack.emplace_back(it->value, m);
  }
}

template <typename T>
void findPeaksImpl(std::span<const T> x, const FindPeaksParams& params, std::vector<Peak>& out) {
  out.clear();
  if (x.size() < 3) return;
  thread_local Scratch s;
  turningPoints(x, s);
  const std::size_t m = s.ext.size();
  if (m < 3) return;

  // Prominence = height above the higher of the two bases.
  s.base_left.resize(m);
  s.base_right.resize(m);
  bases(s.ext.begin(), s.ext.end(), s.stack, s.base_left.data(), 1);
  bases(s.ext.rbegin(), s.ext.rend(), s.stack, s.base_right.data() + m - 1, -1);
  for (std::size_t e = 0; e < m; ++e) {
    const Extremum& ex = s.ext[e];
    if (!ex.is_peak) continue;
    const float prominence = ex.value - std::max(s.base_left[e], s.base_right[e]);
    // A plateau's peak is its middle sample (scipy: the left of two middles).
    if (prominence >= params.min_prominence)
      out.push_back(Peak{(ex.first + ex.last) / 2, ex.value, prominence});
  }

  // Minimum distance: highest peaks first, each removes lower ones within min_distance.
  if (params.min_distance <= 1 || out.size() < 2) return;
  const std::size_t k = out.size();
  s.priority.resize(k);
  std::iota(s.priority.begin(), s.priority.end(), 0u);
  std::stable_sort(s.priority.begin(), s.priority.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return out[a].height > out[b].height; });
  s.removed.assign(k, 0);
  const auto d = static_cast<std::uint32_t>(params.min_distance);
  for (const std::uint32_t p : s.priority) {
    if (s.removed[p]) continue;
    for (std::size_t j = p; j-- > 0 && out[p].index - out[j].index < d;) s.removed[j] = 1;
    for (std::size_t j = p + 1; j < k && out[j].index - out[p].index < d; ++j) s.removed[j] = 1;
  }
  std::size_t w = 0;
  for (std::size_t i = 0; i < k; ++i)
    if (!s.removed[i]) out[w++] = out[i];
  out.resize(w);
}

}  // namespace

void findPeaks(std::span<const std::uint8_t> signal, const FindPeaksParams& params, std::vector<Peak>& out) {
  findPeaksImpl(signal, params, out);
}

void findPeaks(std::span<const float> signal, const FindPeaksParams& params, std::vector<Peak>& out) {
  findPeaksImpl(signal, params, out);
}

}  // namespace radarslam
