#include "radarslam/slam/map_consistency.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include "slam_state.h"

namespace radarslam {

using slam_detail::between;

namespace {

struct PairAccumulator {
  PairConsistency result;
  std::vector<double> errors_m;

  void add(double em, double ed, const MapConsistencyParams& p) {
    ++result.pairs;
    result.consistent += em <= p.max_error_m && ed <= p.max_error_deg;
    errors_m.push_back(em);
    result.worst_error_m = std::max(result.worst_error_m, em);
    result.worst_error_deg = std::max(result.worst_error_deg, ed);
  }

  PairConsistency finish() {
    if (result.pairs > 0) {
      result.fraction = double(result.consistent) / double(result.pairs);
      auto mid = errors_m.begin() + static_cast<std::ptrdiff_t>(errors_m.size() / 2);
      std::nth_element(errors_m.begin(), mid, errors_m.end());
      result.median_error_m = *mid;
    }
    return result;
  }
};

std::int64_t cellKey(double x, double y, double cell) {
  const auto ix = static_cast<std::int64_t>(std::floor(x / cell));
  const auto iy = static_cast<std::int64_t>(std::floor(y / cell));
  return (ix << 32) ^ (iy & 0xffffffff);
}

}  // namespace

MapConsistency evaluateMapConsistency(const KeyframeMap& map, const Trajectory& gt,
                                      const MapConsistencyParams& p) {
  const std::size_t n = map.keyframes.size();
  std::vector<std::optional<mrpt::math::TPose2D>> truth(n);
  std::vector<double> travelled(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    truth[i] = interpolatePose(gt, map.keyframes[i].stamp_ns);
    if (i > 0) {
      travelled[i] = travelled[i - 1];
      if (truth[i] && truth[i - 1])
        travelled[i] += std::hypot(truth[i]->x - truth[i - 1]->x, truth[i]->y - truth[i - 1]->y);
    }
  }
  // Ground-truth positions in cells of pair_distance_m: a pair lies in the same or a neighbouring cell.
  const double cell = p.pair_distance_m;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells;
  for (std::size_t i = 0; i < n; ++i)
    if (truth[i]) cells[cellKey(truth[i]->x, truth[i]->y, cell)].push_back(i);
  PairAccumulator revisits, all;
  for (std::size_t i = 0; i < n; ++i) {
    if (!truth[i]) continue;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = cells.find(cellKey(truth[i]->x + dx * cell, truth[i]->y + dy * cell, cell));
        if (it == cells.end()) continue;
        for (const std::size_t j : it->second) {
          if (j <= i || std::hypot(truth[j]->x - truth[i]->x, truth[j]->y - truth[i]->y) > p.pair_distance_m)
            continue;
          const auto g = between(*truth[i], *truth[j]);
          const auto m = between(map.keyframes[i].pose, map.keyframes[j].pose);
          const double em = std::hypot(m.x - g.x, m.y - g.y);
          const double ed = std::abs(std::remainder(m.phi - g.phi, 2 * M_PI)) * 180 / M_PI;
          all.add(em, ed, p);
          if (travelled[j] - travelled[i] >= p.revisit_gap_m) revisits.add(em, ed, p);
        }
      }
  }
  return {revisits.finish(), all.finish()};
}

}  // namespace radarslam
