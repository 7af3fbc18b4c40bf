#include <gtest/gtest.h>

#include <random>

#include "radarslam/frontend/max_clique.h"

namespace radarslam {
namespace {

DenseGraph randomGraph(int n, double density, std::mt19937& rng) {
  std::bernoulli_distribution edge(density);
  DenseGraph g(n);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (edge(rng)) g.connect(i, j);
  return g;
}

bool isClique(const DenseGraph& g, const std::vector<int>& v) {
  for (std::size_t a = 0; a < v.size(); ++a)
    for (std::size_t b = a + 1; b < v.size(); ++b)
      if (!g.adjacent(v[a], v[b])) return false;
  return true;
}

int bruteForceMaxClique(const DenseGraph& g) {
  const int n = g.size();
  int best = 0;
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> v;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) v.push_back(i);
    if (static_cast<int>(v.size()) > best && isClique(g, v)) best = static_cast<int>(v.size());
  }
  return best;
}

TEST(MaxClique, MatchesBruteForceOnSmallRandomGraphs) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + trial % 14;
    const double density = 0.1 + 0.8 * ((trial * 7) % 10) / 10.0;
    const DenseGraph g = randomGraph(n, density, rng);
    const CliqueResult r = maximumClique(g);
    ASSERT_TRUE(r.exact);
    ASSERT_TRUE(isClique(g, r.vertices)) << "trial " << trial;
    ASSERT_EQ(static_cast<int>(r.vertices.size()), bruteForceMaxClique(g)) << "trial " << trial << " n " << n;
  }
}

TEST(MaxClique, FindsPlantedCliqueAcrossWordBoundaries) {
  std::mt19937 rng(7);
  DenseGraph g = randomGraph(300, 0.2, rng);
  std::vector<int> planted;
  for (int i = 5; i < 300; i += 7) planted.push_back(i);  // 43 vertices spread over 5 words
  for (std::size_t a = 0; a < planted.size(); ++a)
    for (std::size_t b = a + 1; b < planted.size(); ++b) g.connect(planted[a], planted[b]);
  const CliqueResult r = maximumClique(g);
  EXPECT_TRUE(r.exact);
  EXPECT_EQ(r.vertices, planted);  // a G(300, 0.2) has no clique anywhere near 43
}

TEST(MaxClique, BudgetStillReturnsAValidClique) {
  std::mt19937 rng(3);
  const DenseGraph g = randomGraph(200, 0.6, rng);
  const CliqueResult r = maximumClique(g, 5);
  EXPECT_FALSE(r.exact);
  EXPECT_LE(r.steps, 5);
  EXPECT_TRUE(isClique(g, r.vertices));
  EXPECT_GE(r.vertices.size(), 2u);
}

TEST(MaxClique, EmptyAndEdgelessGraphs) {
  EXPECT_TRUE(maximumClique(DenseGraph(0)).vertices.empty());
  const CliqueResult r = maximumClique(DenseGraph(5));
  EXPECT_EQ(r.vertices.size(), 1u);
  DenseGraph g(3);
  g.connect(0, 2);
  EXPECT_EQ(g.edgeCount(), 1u);
  EXPECT_EQ(maximumClique(g).vertices, (std::vector<int>{0, 2}));
}

TEST(DenseGraph, InducedSubgraphRenumbersByTheGivenVertices) {
  DenseGraph g(70);  // edges across the 64-bit word boundary
  g.connect(0, 65);
  g.connect(65, 3);
  g.connect(3, 69);
  const DenseGraph sub = g.induced({65, 3, 0});
  ASSERT_EQ(sub.size(), 3);
  EXPECT_TRUE(sub.adjacent(0, 1));   // 65 - 3
  EXPECT_TRUE(sub.adjacent(0, 2));   // 65 - 0
  EXPECT_FALSE(sub.adjacent(1, 2));  // 3 - 0
  EXPECT_EQ(sub.edgeCount(), 2u);    // 3 - 69 left out with 69
}

}  // namespace
}  // namespace radarslam
