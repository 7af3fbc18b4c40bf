#include "radarslam/radar/find_peaks.h"

#include <algorithm>
#include <numeric>

namespace radarslam {

namespace {

// Per-thread scratch buffers: findPeaks runs once per azimuth, 400 times per scan.
struct Scratch {
  std::vector<std::uint32_t> candidates;
  std::vector<float> base_left, base_right;
  std::vector<std::pair<std::uint32_t, float>> stack;  // (index, min since the entry below)
  std::vector<std::uint32_t> priority;
  std::vector<char> removed;
};

// base[i] = min of x over (g, i], g = the nearest index left of i with x[g] > x[i] (or -1):
// one monotonic-stack pass. Entries hold strictly decreasing values; each keeps the minimum of
// the samples between it and the entry below, so popping merges the minima of covered spans.
template <typename T>
void leftBases(std::span<const T> x, std::vector<std::pair<std::uint32_t, float>>& stack,
               std::vector<float>& base) {
  stack.clear();
  base.resize(x.size());
  for (std::uint32_t i = 0; i < x.size(); ++i) {
    float m = static_cast<float>(x[i]);
    while (!stack.empty() && x[stack.back().first] <= x[i]) {
      m = std::min(m, stack.back().second);
      stack.pop_back();
    }
    base[i] = m;
    stack.emplace_back(i, m);
  }
}

template <typename T>
void rightBases(std::span<const T> x, std::vector<std::pair<std::uint32_t, float>>& stack,
                std::vector<float>& base) {
  stack.clear();
  base.resize(x.size());
  for (std::uint32_t i = static_cast<std::uint32_t>(x.size()); i-- > 0;) {
    float m = static_cast<float>(x[i]);
    while (!stack.empty() && x[stack.back().first] <= x[i]) {
      m = std::min(m, stack.back().second);
      stack.pop_back();
    }
    base[i] = m;
    stack.emplace_back(i, m);
  }
}

template <typename T>
void findPeaksImpl(std::span<const T> x, const FindPeaksParams& params, std::vector<Peak>& out) {
  out.clear();
  const std::size_t n = x.size();
  if (n < 3) return;
  thread_local Scratch s;

  // Local maxima, plateaus reduced to their middle sample (scipy's _local_maxima_1d).
  s.candidates.clear();
  for (std::size_t i = 1; i + 1 < n;) {
    if (x[i - 1] < x[i]) {
      std::size_t ahead = i + 1;
      while (ahead + 1 < n && x[ahead] == x[i]) ++ahead;
      if (x[ahead] < x[i]) {
        s.candidates.push_back(static_cast<std::uint32_t>((i + ahead - 1) / 2));
        i = ahead;
        continue;
      }
    }
    ++i;
  }
  if (s.candidates.empty()) return;

  // Prominence = height above the higher base.
  leftBases(x, s.stack, s.base_left);
  rightBases(x, s.stack, s.base_right);
  for (const std::uint32_t i : s.candidates) {
    const float h = static_cast<float>(x[i]);
    const float prominence = h - std::max(s.base_left[i], s.base_right[i]);
    if (prominence >= params.min_prominence) out.push_back(Peak{i, h, prominence});
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
