#include "radarslam/frontend/max_clique.h"

#include <algorithm>
#include <bit>
#include <numeric>

namespace radarslam {

DenseGraph::DenseGraph(int n)
    : n_(n), words_((n + 63) / 64), bits_(static_cast<std::size_t>(n) * words_, 0) {}

void DenseGraph::connect(int i, int j) {
  if (i == j) return;
  bits_[static_cast<std::size_t>(i) * words_ + (j >> 6)] |= std::uint64_t{1} << (j & 63);
  bits_[static_cast<std::size_t>(j) * words_ + (i >> 6)] |= std::uint64_t{1} << (i & 63);
}

int DenseGraph::degree(int i) const {
  int d = 0;
  for (int w = 0; w < words_; ++w) d += std::popcount(row(i)[w]);
  return d;
}

DenseGraph DenseGraph::induced(const std::vector<int>& vertices) const {
  const int n = static_cast<int>(vertices.size());
  DenseGraph sub(n);
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      if (adjacent(vertices[a], vertices[b])) sub.connect(a, b);
  return sub;
}

std::size_t DenseGraph::edgeCount() const {
  std::size_t twice = 0;
  for (int i = 0; i < n_; ++i) twice += static_cast<std::size_t>(degree(i));
  return twice / 2;
}

namespace {

using Bits = std::vector<std::uint64_t>;

/// Branch and bound on a graph whose vertices are renumbered by decreasing degree (BBMC).
class Search {
 public:
  Search(const DenseGraph& g, long max_steps) : g_(g), max_steps_(max_steps) {}

  void run() {
    // Greedy start (highest-degree-first, which is vertex order here): a valid answer even if the
    // budget runs out before the first leaf, and an initial bound for the search.
    Bits cand(g_.words(), 0);
    for (int v = 0; v < g_.size(); ++v) cand[v >> 6] |= std::uint64_t{1} << (v & 63);
    for (int v = 0; v < g_.size(); ++v) {
      if (!((cand[v >> 6] >> (v & 63)) & 1u)) continue;
      best.push_back(v);
      const std::uint64_t* nv = g_.row(v);
      for (int w = 0; w < g_.words(); ++w) cand[w] &= nv[w];
    }
    Bits all(g_.words(), 0);
    for (int v = 0; v < g_.size(); ++v) all[v >> 6] |= std::uint64_t{1} << (v & 63);
    expand(all);
  }

  std::vector<int> best;
  bool exhausted = false;
  long steps = 0;

 private:
  static bool empty(const Bits& b) {
    return std::all_of(b.begin(), b.end(), [](std::uint64_t w) { return w == 0; });
  }

  /// Greedy sequential colouring of `p` (Tomita): vertices in order of non-decreasing colour.
  void colour(const Bits& p, std::vector<int>& order, std::vector<int>& colours) const {
    Bits uncoloured = p, q(p.size());
    int k = 0;
    while (!empty(uncoloured)) {
      ++k;
      q = uncoloured;
      for (std::size_t w = 0; w < q.size(); ++w) {
        while (q[w]) {
          const int v = static_cast<int>(w * 64 + std::countr_zero(q[w]));
          uncoloured[w] &= ~(std::uint64_t{1} << (v & 63));
          q[w] &= ~(std::uint64_t{1} << (v & 63));
          const std::uint64_t* nv = g_.row(v);
          for (std::size_t u = w; u < q.size(); ++u) q[u] &= ~nv[u];  // neighbours need another colour
          order.push_back(v);
          colours.push_back(k);
        }
      }
    }
  }

  void expand(const Bits& p) {
    if (max_steps_ > 0 && steps >= max_steps_) {
      exhausted = true;
      return;
    }
    ++steps;
    std::vector<int> order, colours;
    colour(p, order, colours);
    Bits cand = p, next(p.size());
    for (int i = static_cast<int>(order.size()) - 1; i >= 0; --i) {
      // Bound: this clique plus at most colours[i] more vertices cannot beat the best.
      if (current_.size() + static_cast<std::size_t>(colours[i]) <= best.size()) return;
      const int v = order[i];
      current_.push_back(v);
      const std::uint64_t* nv = g_.row(v);
      for (std::size_t w = 0; w < cand.size(); ++w) next[w] = cand[w] & nv[w];
      if (empty(next)) {
        if (current_.size() > best.size()) best = current_;
      } else {
        expand(next);
      }
      current_.pop_back();
      cand[v >> 6] &= ~(std::uint64_t{1} << (v & 63));
      if (exhausted) return;
    }
  }

  const DenseGraph& g_;
  long max_steps_;
  std::vector<int> current_;
};

}  // namespace

CliqueResult maximumClique(const DenseGraph& graph, long max_steps) {
  CliqueResult out;
  const int n = graph.size();
  if (n == 0) return out;
  // Renumber by decreasing degree: colouring then bounds tightly and big cliques come first.
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::vector<int> deg(n);
  for (int i = 0; i < n; ++i) deg[i] = graph.degree(i);
  std::stable_sort(perm.begin(), perm.end(), [&](int a, int b) { return deg[a] > deg[b]; });
  const DenseGraph sorted = graph.induced(perm);

  Search search(sorted, max_steps);
  search.run();
  for (int v : search.best) out.vertices.push_back(perm[v]);
  std::sort(out.vertices.begin(), out.vertices.end());
  out.exact = !search.exhausted;
  out.steps = search.steps;
  return out;
}

}  // namespace radarslam
