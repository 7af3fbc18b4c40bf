#include "radarslam/sim/road.h"

#include <algorithm>
#include <cmath>

namespace radarslam::sim {

double distanceToSegment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  const double l2 = e.dot(e);
  const double t = l2 > 0 ? std::clamp((p - a).dot(e) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + e * t)).norm();
}

RoadIndex::RoadIndex(const std::vector<RoadPiece>& pieces, double cell_m) : pieces_(pieces), cell_(cell_m) {
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  double max_hw = 0;
  for (const auto& r : pieces_) {
    xmin = std::min({xmin, r.a.x, r.b.x}), xmax = std::max({xmax, r.a.x, r.b.x});
    ymin = std::min({ymin, r.a.y, r.b.y}), ymax = std::max({ymax, r.a.y, r.b.y});
    max_hw = std::max(max_hw, r.half_width);
  }
  if (pieces_.empty()) return;
  // A piece is listed in every cell within (its half-width + one cell) of it, so a query looking
  // at its own cell finds every piece whose clearance is below one cell.
  reach_ = max_hw + cell_;
  x0_ = xmin - reach_ - cell_, y0_ = ymin - reach_ - cell_;
  nx_ = static_cast<int>((xmax + reach_ + cell_ - x0_) / cell_) + 2;
  ny_ = static_cast<int>((ymax + reach_ + cell_ - y0_) / cell_) + 2;
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(nx_) * ny_);
  for (std::uint32_t k = 0; k < pieces_.size(); ++k) {
    const auto& r = pieces_[k];
    const double grow = r.half_width + cell_;
    const int cx0 = static_cast<int>((std::min(r.a.x, r.b.x) - grow - x0_) / cell_);
    const int cx1 = static_cast<int>((std::max(r.a.x, r.b.x) + grow - x0_) / cell_);
    const int cy0 = static_cast<int>((std::min(r.a.y, r.b.y) - grow - y0_) / cell_);
    const int cy1 = static_cast<int>((std::max(r.a.y, r.b.y) + grow - y0_) / cell_);
    for (int cy = std::max(cy0, 0); cy <= std::min(cy1, ny_ - 1); ++cy)
      for (int cx = std::max(cx0, 0); cx <= std::min(cx1, nx_ - 1); ++cx) {
        const Vec2 c{x0_ + (cx + 0.5) * cell_, y0_ + (cy + 0.5) * cell_};
        if (distanceToSegment(c, r.a, r.b) <= grow + cell_ * 0.75) cells[cy * nx_ + cx].push_back(k);
      }
  }
  start_.assign(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    items_.insert(items_.end(), cells[c].begin(), cells[c].end());
    start_[c + 1] = static_cast<std::uint32_t>(items_.size());
  }
}

double RoadIndex::clearance(Vec2 p, double cap) const {
  const int cx = static_cast<int>(std::floor((p.x - x0_) / cell_));
  const int cy = static_cast<int>(std::floor((p.y - y0_) / cell_));
  if (pieces_.empty() || cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return cap;
  double best = cap;
  const std::size_t c = static_cast<std::size_t>(cy) * nx_ + cx;
  for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
    const auto& r = pieces_[items_[k]];
    best = std::min(best, distanceToSegment(p, r.a, r.b) - r.half_width);
  }
  return best;
}

}  // namespace radarslam::sim
