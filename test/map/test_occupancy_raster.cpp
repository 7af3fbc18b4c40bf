// buildOccupancy against a plain reference: the same ray casting with each keyframe's hits and
// misses de-duplicated by std::set over whole-grid indices. The raster must match bit for bit,
// whatever the de-duplication does inside (today: a window over each keyframe's footprint).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "radarslam/map/map_exports.h"
#include "synthetic_map.h"

namespace radarslam {
namespace {

// Grid geometry copied from the raster under test (bounds are checked separately); the ray
// casting and the log-odds updates are re-derived from the documented rule (map_exports.h).
OccupancyRaster referenceOccupancy(const KeyframeMap& map, const GridExportParams& p,
                                   const OccupancyRaster& geometry) {
  OccupancyRaster out = geometry;
  const std::size_t cells = static_cast<std::size_t>(out.width) * out.height;
  std::vector<float> lo(cells, 0.f);
  out.observed.assign(cells, 0);
  const double res = out.resolution;
  auto col = [&](double x) { return static_cast<int>(std::floor((x - out.x_min) / res)); };
  auto row = [&](double y) { return static_cast<int>(std::floor((y - out.y_min) / res)); };
  auto inside = [&](int c, int r) { return c >= 0 && r >= 0 && c < out.width && r < out.height; };
  const int sectors = static_cast<int>(map.meta.sensor.num_azimuths);
  for (const auto& kf : map.keyframes) {
    std::set<std::size_t> hits, misses;
    std::vector<double> nearest(sectors, std::numeric_limits<double>::infinity());
    std::vector<std::pair<int, int>> end(sectors);
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& pt : kf.points) {
      const double wx = kf.pose.x + c * pt.x - s * pt.y, wy = kf.pose.y + s * pt.x + c * pt.y;
      if (inside(col(wx), row(wy))) hits.insert(static_cast<std::size_t>(row(wy)) * out.width + col(wx));
      double a = std::atan2(pt.y, pt.x);
      if (a < 0) a += 2 * M_PI;
      const int k = std::min(static_cast<int>(a / (2 * M_PI) * sectors), sectors - 1);
      const float r = std::hypot(pt.x, pt.y);
      if (r < nearest[k]) nearest[k] = r, end[k] = {col(wx), row(wy)};
    }
    const int c0 = col(kf.pose.x), r0 = row(kf.pose.y);
    for (int k = 0; k < sectors; ++k) {
      if (!std::isfinite(nearest[k])) continue;
      const auto [c1, r1] = end[k];
      int x = c0, y = r0;
      const int dx = std::abs(c1 - c0), dy = -std::abs(r1 - r0), sx = c0 < c1 ? 1 : -1, sy = r0 < r1 ? 1 : -1;
      for (int err = dx + dy; !(x == c1 && y == r1);) {
        if (inside(x, y)) misses.insert(static_cast<std::size_t>(y) * out.width + x);
        const int e2 = 2 * err;
        if (e2 >= dy) err += dy, x += sx;
        if (e2 <= dx) err += dx, y += sy;
      }
    }
    const auto clamp = static_cast<float>(p.log_odds_clamp);
    for (const std::size_t i : misses) {
      out.observed[i] = 1;
      if (!hits.count(i)) lo[i] = std::max(-clamp, lo[i] + static_cast<float>(p.log_odds_miss));
    }
    for (const std::size_t i : hits) {
      out.observed[i] = 1;
      lo[i] = std::min(clamp, lo[i] + static_cast<float>(p.log_odds_hit));
    }
  }
  out.p_occupied.resize(cells);
  for (std::size_t i = 0; i < cells; ++i) out.p_occupied[i] = 1.f / (1.f + std::exp(-lo[i]));
  return out;
}

void expectSameRaster(const KeyframeMap& map, const GridExportParams& p) {
  const OccupancyRaster got = buildOccupancy(map, p);
  ASSERT_GT(got.width, 0);
  const OccupancyRaster want = referenceOccupancy(map, p, got);
  ASSERT_EQ(got.p_occupied.size(), want.p_occupied.size());
  ASSERT_EQ(got.observed.size(), want.observed.size());
  std::size_t differing = 0, observed = 0, occupied = 0, free = 0;
  for (std::size_t i = 0; i < want.p_occupied.size(); ++i) {
    differing += got.p_occupied[i] != want.p_occupied[i] || got.observed[i] != want.observed[i];
    observed += want.observed[i];
    occupied += want.p_occupied[i] > 0.5f;
    free += want.p_occupied[i] < 0.5f;
  }
  EXPECT_EQ(differing, 0u);
  // Not a vacuous comparison: the map has hit, free and unobserved cells.
  EXPECT_GT(occupied, 0u);
  EXPECT_GT(free, 0u);
  EXPECT_LT(observed, want.observed.size());
}

// Keyframes along a random walk, each seeing random returns up to 60 m: rays of every length and
// direction, keyframes that overlap and revisit cells.
KeyframeMap randomWalkMap(unsigned seed, int keyframes) {
  KeyframeMap map = test::syntheticMap(1, 1);
  map.keyframes.clear();
  map.meta.sensor.num_azimuths = 400;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  double x = 0, y = 0, phi = 0;
  for (int k = 0; k < keyframes; ++k) {
    Keyframe kf;
    kf.id = k;
    phi += 0.3 * (u(rng) - 0.5);
    x += 3 * std::cos(phi), y += 3 * std::sin(phi);
    kf.pose = {x, y, phi};
    for (int i = 0; i < 1500; ++i) {
      const double a = 2 * M_PI * u(rng), r = 1 + 59 * u(rng);
      kf.points.push_back({static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 80.f});
    }
    map.keyframes.push_back(std::move(kf));
  }
  return map;
}

TEST(OccupancyRaster, MatchesThePlainReferenceOnTheSyntheticMap) {
  expectSameRaster(test::syntheticMap(), {});
  GridExportParams fine;
  fine.resolution_m = 0.05;
  expectSameRaster(test::syntheticMap(5, 720), fine);
}

TEST(OccupancyRaster, MatchesThePlainReferenceAlongARandomWalk) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    expectSameRaster(randomWalkMap(seed, 40), {});
  }
}

// With no margin the farthest returns lie on the grid's last edge (or just outside it by
// rounding): rays to them must be clipped, not dropped.
TEST(OccupancyRaster, MatchesThePlainReferenceWithoutAMargin) {
  GridExportParams p;
  p.margin_m = 0;
  p.resolution_m = 0.5;
  expectSameRaster(randomWalkMap(7, 25), p);
  expectSameRaster(test::syntheticMap(), p);
}

}  // namespace
}  // namespace radarslam
