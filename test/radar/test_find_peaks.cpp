// findPeaks: hand-checked prominences and distance suppression, plus agreement with a direct
// (quadratic) transcription of the MATLAB/scipy definitions on random signals.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <radarslam/radar/find_peaks.h>

namespace radarslam {
namespace {

std::vector<std::uint32_t> indices(const std::vector<Peak>& peaks) {
  std::vector<std::uint32_t> out;
  for (const Peak& p : peaks) out.push_back(p.index);
  return out;
}

// index:                                   0  1   2  3  4  5   6   7   8  9   10 11
const std::vector<std::uint8_t> kSignal = {0, 10, 3, 6, 2, 20, 20, 20, 4, 15, 1, 0};

TEST(FindPeaks, HandBuiltSignalProminences) {
  // Maxima: 1, 3, the plateau 5..7 (middle 6), 9. Prominences worked out by hand:
  //  1: bases min[0..1]=0 (no higher left), min[1..4]=2 (20 at 5)   -> 10 - 2 = 8
  //  3: bases min[2..3]=3 (10 at 1), min[3..4]=2 (20 at 5)          -> 6 - 3 = 3
  //  6: no higher sample either side, bases 0 and 0                  -> 20
  //  9: bases min[8..9]=4 (20 at 7), min[9..11]=0                    -> 15 - 4 = 11
  const auto all = findPeaks(std::span(kSignal));
  ASSERT_EQ(indices(all), (std::vector<std::uint32_t>{1, 3, 6, 9}));
  EXPECT_FLOAT_EQ(all[0].prominence, 8);
  EXPECT_FLOAT_EQ(all[1].prominence, 3);
  EXPECT_FLOAT_EQ(all[2].prominence, 20);
  EXPECT_FLOAT_EQ(all[3].prominence, 11);
  EXPECT_FLOAT_EQ(all[2].height, 20);

  EXPECT_EQ(indices(findPeaks(std::span(kSignal), {5.0, 1})), (std::vector<std::uint32_t>{1, 6, 9}));
  EXPECT_EQ(indices(findPeaks(std::span(kSignal), {8.0, 1})), (std::vector<std::uint32_t>{1, 6, 9}));
  EXPECT_EQ(indices(findPeaks(std::span(kSignal), {8.5, 1})), (std::vector<std::uint32_t>{6, 9}));
  EXPECT_EQ(indices(findPeaks(std::span(kSignal), {21.0, 1})), (std::vector<std::uint32_t>{}));
}

TEST(FindPeaks, DistanceKeepsTheHighestFirst) {
  // After prominence >= 5: {1, 6, 9}. Distance 4: 6 (20) removes 9 (3 apart); 1 is 5 away.
  EXPECT_EQ(indices(findPeaks(std::span(kSignal), {5.0, 4})), (std::vector<std::uint32_t>{1, 6}));
  // Distance 3: 9 is exactly 3 away and stays (kept peaks are >= distance apart).
  EXPECT_EQ(indices(findPeaks(std::span(kSignal), {5.0, 3})), (std::vector<std::uint32_t>{1, 6, 9}));
  // Distance 6: 6 removes both.
  EXPECT_EQ(indices(findPeaks(std::span(kSignal), {5.0, 6})), (std::vector<std::uint32_t>{6}));
  // A removed peak does not remove others: 30 at 10 removes 25 at 14, so 20 at 18 survives.
  std::vector<std::uint8_t> x(24, 0);
  x[10] = 30;
  x[14] = 25;
  x[18] = 20;
  EXPECT_EQ(indices(findPeaks(std::span(x), {0.0, 5})), (std::vector<std::uint32_t>{10, 18}));
  // Equal heights: the lower index wins.
  x[14] = 30;
  EXPECT_EQ(indices(findPeaks(std::span(x), {0.0, 5})), (std::vector<std::uint32_t>{10, 18}));
}

TEST(FindPeaks, EdgesAndPlateaus) {
  const std::vector<std::uint8_t> edge = {9, 1, 1, 5, 5, 5, 5, 1, 7};  // ends are never peaks
  const auto p = findPeaks(std::span(edge));
  ASSERT_EQ(indices(p), (std::vector<std::uint32_t>{4}));  // plateau 3..6 -> (3 + 6) / 2
  EXPECT_FLOAT_EQ(p[0].prominence, 4);
  const std::vector<std::uint8_t> open_plateau = {0, 5, 5, 5};  // runs into the end: no peak
  EXPECT_TRUE(findPeaks(std::span(open_plateau)).empty());
  const std::vector<std::uint8_t> tiny = {0, 5};
  EXPECT_TRUE(findPeaks(std::span(tiny)).empty());
}

// Direct transcription of the definitions (scipy's _local_maxima_1d and _peak_prominences, and
// the distance rule), quadratic time.
std::vector<Peak> reference(const std::vector<float>& x, double min_prom, int min_dist) {
  std::vector<Peak> peaks;
  const std::size_t n = x.size();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (!(x[i - 1] < x[i])) continue;
    std::size_t j = i;
    while (j + 1 < n && x[j + 1] == x[i]) ++j;
    if (j + 1 < n && x[j + 1] < x[i]) {
      const std::size_t p = (i + j) / 2;
      float lmin = x[p], rmin = x[p];
      for (std::size_t k = p + 1; k-- > 0 && x[k] <= x[p];) lmin = std::min(lmin, x[k]);
      for (std::size_t k = p; k < n && x[k] <= x[p]; ++k) rmin = std::min(rmin, x[k]);
      const float prom = x[p] - std::max(lmin, rmin);
      if (prom >= min_prom) peaks.push_back({static_cast<std::uint32_t>(p), x[p], prom});
    }
    i = j;
  }
  std::vector<char> keep(peaks.size(), 1);
  std::vector<std::size_t> order(peaks.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](auto a, auto b) { return peaks[a].height > peaks[b].height; });
  for (std::size_t oi = 0; oi < order.size(); ++oi) {
    const std::size_t a = order[oi];
    if (!keep[a]) continue;
    for (std::size_t b = 0; b < peaks.size(); ++b)
      if (b != a && keep[b] && std::abs(int(peaks[a].index) - int(peaks[b].index)) < min_dist &&
          std::find(order.begin(), order.begin() + oi, b) == order.begin() + oi)
        keep[b] = 0;
  }
  std::vector<Peak> out;
  for (std::size_t i = 0; i < peaks.size(); ++i)
    if (keep[i]) out.push_back(peaks[i]);
  return out;
}

TEST(FindPeaks, AgreesWithTheDefinitionOnRandomSignals) {
  std::mt19937 rng(42);
  std::size_t total = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = 3 + rng() % 400;
    const int levels = 2 + static_cast<int>(rng() % 60);  // few levels -> many plateaus and ties
    std::vector<std::uint8_t> x8(n);
    std::vector<float> xf(n);
    for (std::size_t i = 0; i < n; ++i) {
      x8[i] = static_cast<std::uint8_t>(rng() % levels * (255 / levels));
      xf[i] = x8[i];
    }
    const double prom = static_cast<double>(rng() % 80);
    const int dist = 1 + static_cast<int>(rng() % 25);
    const auto want = reference(xf, prom, dist);
    const auto got8 = findPeaks(std::span<const std::uint8_t>(x8), {prom, dist});
    const auto gotf = findPeaks(std::span<const float>(xf), {prom, dist});
    ASSERT_EQ(indices(got8), indices(want)) << "trial " << trial;
    ASSERT_EQ(indices(gotf), indices(want)) << "trial " << trial;
    for (std::size_t i = 0; i < want.size(); ++i) ASSERT_FLOAT_EQ(got8[i].prominence, want[i].prominence);
    total += want.size();
  }
  EXPECT_GT(total, 1000u);  // the trials did exercise peaks
}

}  // namespace
}  // namespace radarslam
