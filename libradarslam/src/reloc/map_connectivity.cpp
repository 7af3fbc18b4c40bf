// Keyframe graph of a stored map and bounded path distances; see reloc/map_connectivity.h.
#include "radarslam/reloc/map_connectivity.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>
#include <utility>

namespace radarslam {

MapConnectivity::MapConnectivity(const KeyframeMap& map) : adjacency_(map.keyframes.size()) {
  std::unordered_map<std::uint64_t, std::size_t> index;
  for (std::size_t k = 0; k < map.keyframes.size(); ++k) index.emplace(map.keyframes[k].id, k);
  auto link = [&](std::size_t a, std::size_t b, double length) {
    if (a == b) return;
    adjacency_[a].push_back({b, length});
    adjacency_[b].push_back({a, length});
  };
  std::size_t used = 0;
  for (const auto& e : map.edges) {
    const auto a = index.find(e.from), b = index.find(e.to);
    if (a == index.end() || b == index.end()) continue;
    const double length = std::hypot(e.relative.x, e.relative.y);
    if (!std::isfinite(length)) continue;
    link(a->second, b->second, length);
    ++used;
  }
  if (used == 0)
    for (std::size_t k = 1; k < map.keyframes.size(); ++k) {
      const auto& p = map.keyframes[k - 1].pose;
      const auto& q = map.keyframes[k].pose;
      link(k - 1, k, std::hypot(q.x - p.x, q.y - p.y));
    }
}

MapConnectivity::Search MapConnectivity::search(std::size_t from, double max_path_m,
                                                std::size_t stop_at) const {
  const std::size_t n = adjacency_.size();
  Search r{std::vector<double>(n, std::numeric_limits<double>::infinity()), std::vector<std::size_t>(n, n)};
  std::vector<char> settled(n, 0);
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  r.distance[from] = 0;
  queue.push({0, from});
  while (!queue.empty()) {
    const auto [d, k] = queue.top();
    queue.pop();
    if (d > r.distance[k] || settled[k]) continue;
    settled[k] = 1;
    if (k == stop_at) break;
    for (const Link& l : adjacency_[k]) {
      const double nd = d + l.length_m;
      if (nd <= max_path_m && nd < r.distance[l.to]) {
        r.distance[l.to] = nd;
        r.previous[l.to] = k;
        queue.push({nd, l.to});
      }
    }
  }
  return r;
}

std::vector<char> MapConnectivity::within(std::size_t from, double max_path_m) const {
  if (from >= adjacency_.size()) return std::vector<char>(adjacency_.size(), 1);
  const Search r = search(from, max_path_m, adjacency_.size());
  std::vector<char> out(adjacency_.size(), 0);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = std::isfinite(r.distance[k]) ? 1 : 0;
  return out;
}

std::vector<std::size_t> MapConnectivity::path(std::size_t from, std::size_t to) const {
  const std::size_t n = adjacency_.size();
  if (from >= n || to >= n) return {};
  const Search r = search(from, std::numeric_limits<double>::infinity(), to);
  if (!std::isfinite(r.distance[to])) return {};
  std::vector<std::size_t> out{to};
  while (out.back() != from) out.push_back(r.previous[out.back()]);
  std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace radarslam
