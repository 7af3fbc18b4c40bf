#pragma once
// Maximum clique of an undirected graph (paper Sec. III-A: the largest set of mutually consistent
// keypoint matches). Exact branch and bound with greedy-colouring bounds on bitsets (Tomita's MCQ /
// San Segundo's BBMC), with an optional step budget: when the budget runs out the largest clique
// found so far is returned and `exact` is false.
#include <cstdint>
#include <vector>

namespace radarslam {

/// Symmetric adjacency matrix stored as one bitset row per vertex; no self loops.
class DenseGraph {
 public:
  explicit DenseGraph(int n = 0);
  int size() const { return n_; }
  int words() const { return words_; }
  void connect(int i, int j);
  bool adjacent(int i, int j) const { return (row(i)[j >> 6] >> (j & 63)) & 1u; }
  const std::uint64_t* row(int i) const { return bits_.data() + static_cast<std::size_t>(i) * words_; }
  int degree(int i) const;
  std::size_t edgeCount() const;
  /// The subgraph on `vertices`: its vertex k is vertices[k] of this graph.
  DenseGraph induced(const std::vector<int>& vertices) const;

 private:
  int n_ = 0, words_ = 0;
  std::vector<std::uint64_t> bits_;
};

struct CliqueResult {
  std::vector<int> vertices;  ///< sorted ascending
  bool exact = true;          ///< false if the step budget stopped the search
  long steps = 0;             ///< branch-and-bound nodes expanded
};

/// max_steps <= 0: no budget (always exact).
CliqueResult maximumClique(const DenseGraph& graph, long max_steps = 0);

}  // namespace radarslam
