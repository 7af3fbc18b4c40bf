#include "radarslam/frontend/consistency_graph.h"

#include <cmath>

namespace radarslam {

DenseGraph buildConsistencyGraph(const Correspondences& matches, double delta_c_m, ConsistencyTest test) {
  const int n = static_cast<int>(matches.size());
  DenseGraph g(n);
  if (test == ConsistencyTest::DisplacementLength) {
    std::vector<double> len(n);
    for (int i = 0; i < n; ++i) len[i] = (matches[i].cur - matches[i].ref).norm();
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (std::abs(len[i] - len[j]) < delta_c_m) g.connect(i, j);
    return g;
  }
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& ci = matches[i].cur;
    const Eigen::Vector2d& ri = matches[i].ref;
    for (int j = i + 1; j < n; ++j) {
      const double dc = (ci - matches[j].cur).norm();
      const double dr = (ri - matches[j].ref).norm();
      if (std::abs(dc - dr) < delta_c_m) g.connect(i, j);
    }
  }
  return g;
}

}  // namespace radarslam
