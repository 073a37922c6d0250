#include "engine/cluster/normalized_cut.h"

#include <random>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "engine/cluster/spectral_split.h"

namespace motif {
namespace {

using Groups = std::vector<std::vector<uint32_t>>;

// Cliques of the given sizes (weight `inside`), numbered consecutively, joined in a chain by
// single edges of weight bridges[i] between clique i's last node and clique i+1's first.
SimilarityGraph Cliques(const std::vector<uint32_t>& sizes, double inside,
                        const std::vector<double>& bridges) {
  std::vector<WeightedEdge> edges;
  uint32_t first = 0;
  std::vector<uint32_t> firsts;
  for (uint32_t size : sizes) {
    firsts.push_back(first);
    for (uint32_t a = first; a < first + size; ++a) {
      for (uint32_t b = a + 1; b < first + size; ++b) edges.push_back({a, b, inside});
    }
    first += size;
  }
  for (size_t idx = 0; idx < bridges.size(); ++idx) {
    edges.push_back({firsts[idx + 1] - 1, firsts[idx + 1], bridges[idx]});
  }
  return SimilarityGraph::FromEdges(first, edges);
}

Groups Consecutive(const std::vector<uint32_t>& sizes) {
  Groups groups;
  uint32_t first = 0;
  for (uint32_t size : sizes) {
    groups.emplace_back();
    for (uint32_t node = first; node < first + size; ++node) groups.back().push_back(node);
    first += size;
  }
  return groups;
}

// `clusters` groups of `size` nodes with random edges inside (probability p_in, weights 0.5..2)
// and sparse weak noise between them; node ids interleaved so clusters are not contiguous.
SimilarityGraph NoisyClusters(uint32_t clusters, uint32_t size, double p_in, uint32_t noise_edges,
                              uint64_t seed, Groups* truth) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const uint32_t n = clusters * size;
  truth->assign(clusters, {});
  for (uint32_t node = 0; node < n; ++node) (*truth)[node % clusters].push_back(node);
  std::vector<WeightedEdge> edges;
  for (const auto& group : *truth) {
    for (size_t a = 0; a < group.size(); ++a) {
      edges.push_back({group[a], group[(a + 1) % group.size()], 1.0});  // a ring: connected
      for (size_t b = a + 1; b < group.size(); ++b) {
        if (unit(random) < p_in) edges.push_back({group[a], group[b], 0.5 + 1.5 * unit(random)});
      }
    }
  }
  for (uint32_t idx = 0; idx < noise_edges; ++idx) {
    edges.push_back({static_cast<uint32_t>(random() % n), static_cast<uint32_t>(random() % n),
                     0.05 * unit(random)});
  }
  return SimilarityGraph::FromEdges(n, edges);
}

TEST(SimilarityGraphTest, SymmetricRowsSummedDuplicatesAndComponents) {
  SimilarityGraph graph = SimilarityGraph::FromEdges(
      6, {{0, 1, 1.0}, {1, 0, 0.5}, {2, 2, 9.0}, {3, 4, 2.0}, {4, 5, 0.0}});
  EXPECT_EQ(graph.edge_count(), 2u);
  EXPECT_DOUBLE_EQ(graph.Degree(0), 1.5);
  EXPECT_DOUBLE_EQ(graph.Degree(1), 1.5);
  EXPECT_DOUBLE_EQ(graph.Degree(2), 0.0);  // self-loops are ignored
  EXPECT_EQ(graph.ConnectedComponents(), (Groups{{0, 1}, {2}, {3, 4}, {5}}));
  SimilarityGraph induced = graph.Induced({1, 3, 4});
  EXPECT_EQ(induced.node_count(), 3u);
  EXPECT_EQ(induced.edge_count(), 1u);
  EXPECT_DOUBLE_EQ(induced.Degree(1), 2.0);
}

TEST(SpectralSplitTest, SweepCutOnAPathFindsTheWeakEdge) {
  // 0 -1- 1 -0.1- 2 -1- 3
  SimilarityGraph graph = SimilarityGraph::FromEdges(4, {{0, 1, 1}, {1, 2, 0.1}, {2, 3, 1}});
  TwoWayCut cut = BestSweepCut(graph, {0.0, 1.0, 2.0, 3.0}, 1);
  EXPECT_EQ(cut.side_a, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(cut.side_b, (std::vector<uint32_t>{2, 3}));
  EXPECT_NEAR(cut.ncut, 2 * 0.1 / 2.1, 1e-12);
  EXPECT_NEAR(NormalizedCutValue(graph, {true, true, false, false}), cut.ncut, 1e-12);
  // The Fiedler vector orders the path, so the spectral cut is the same.
  FiedlerVector fiedler = ComputeFiedlerVector(graph, {});
  ASSERT_EQ(fiedler.values.size(), 4u);
  TwoWayCut spectral = BestSweepCut(graph, fiedler.values, 1);
  EXPECT_EQ(std::min(spectral.side_a, spectral.side_b), (std::vector<uint32_t>{0, 1}));
  // A side may not be smaller than min_side.
  EXPECT_TRUE(BestSweepCut(graph, {0.0, 1.0, 2.0, 3.0}, 3).side_a.empty());
}

TEST(SpectralSplitTest, LanczosAgreesWithTheDenseSolver) {
  Groups truth;
  SimilarityGraph graph = NoisyClusters(2, 300, 0.05, 200, 1, &truth);
  SpectralOptions dense;
  dense.dense_max_nodes = 1000;
  SpectralOptions sparse;
  sparse.dense_max_nodes = 10;
  FiedlerVector a = ComputeFiedlerVector(graph, dense);
  FiedlerVector b = ComputeFiedlerVector(graph, sparse);
  ASSERT_FALSE(a.sparse);
  ASSERT_TRUE(b.sparse);
  ASSERT_EQ(b.values.size(), 600u);
  EXPECT_NEAR(a.eigenvalue, b.eigenvalue, 1e-6);
  TwoWayCut cut_a = BestSweepCut(graph, a.values, 2);
  TwoWayCut cut_b = BestSweepCut(graph, b.values, 2);
  EXPECT_EQ(std::min(cut_a.side_a, cut_a.side_b), truth[0]);
  EXPECT_EQ(std::min(cut_b.side_a, cut_b.side_b), truth[0]);
}

// A graph large enough for the Lanczos products to sum their rows in parallel (about 66,000
// directed edges, above the 32,768 of spectral_split.cc): the same vector, bit for bit, on one thread and on two, and the right cut.
TEST(SpectralSplitTest, LanczosOnALargeGraphGivesTheSameVectorOnAnyThreadCount) {
  Groups truth;
  SimilarityGraph graph = NoisyClusters(2, 400, 0.2, 400, 3, &truth);
  ASSERT_GT(graph.edge_count(), 30000u);  // undirected
  std::vector<FiedlerVector> vectors;
  for (int threads : {1, 2}) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
    vectors.push_back(ComputeFiedlerVector(graph, SpectralOptions{}));
  }
  ASSERT_TRUE(vectors[0].sparse);
  ASSERT_EQ(vectors[0].values.size(), 800u);
  EXPECT_EQ(vectors[0].values, vectors[1].values);
  EXPECT_EQ(vectors[0].eigenvalue, vectors[1].eigenvalue);
  TwoWayCut cut = BestSweepCut(graph, vectors[0].values, 2);
  EXPECT_EQ(std::min(cut.side_a, cut.side_b), truth[0]);
}

TEST(NormalizedCutTest, AutomaticFindsTwoCliquesJoinedByAWeakBridge) {
  NormalizedCutStats stats;
  Groups groups = ClusterByNormalizedCut(Cliques({5, 5}, 1.0, {0.2}), {}, &stats);
  EXPECT_EQ(groups, Consecutive({5, 5}));
  EXPECT_EQ(stats.components, 1u);
  EXPECT_EQ(stats.spectral_cuts, 1u);
}

TEST(NormalizedCutTest, AutomaticFindsThreeCliquesOfDifferentSizes) {
  EXPECT_EQ(ClusterByNormalizedCut(Cliques({6, 4, 8}, 1.0, {0.3, 0.5}), {}),
            Consecutive({6, 4, 8}));
}

TEST(NormalizedCutTest, AutomaticKeepsOneCliqueWhole) {
  NormalizedCutStats stats;
  EXPECT_EQ(ClusterByNormalizedCut(Cliques({9}, 1.0, {}), {}, &stats), Consecutive({9}));
  EXPECT_EQ(stats.spectral_cuts, 0u);
  EXPECT_EQ(stats.eigen_solves, 1u);
}

TEST(NormalizedCutTest, GivenGroupsCutsTheCheapestFirst) {
  // Bridges 0.5 (cliques 0-1) and 0.05 (cliques 1-2): with G = 2 only the weak one is cut.
  NormalizedCutOptions options;
  options.groups = 2;
  EXPECT_EQ(ClusterByNormalizedCut(Cliques({5, 5, 5}, 1.0, {0.5, 0.05}), options),
            Consecutive({10, 5}));
  options.groups = 3;
  EXPECT_EQ(ClusterByNormalizedCut(Cliques({5, 5, 5}, 1.0, {0.5, 0.05}), options),
            Consecutive({5, 5, 5}));
  // G = 4 cuts a clique: the best it can do, still no side below two nodes.
  options.groups = 4;
  Groups four = ClusterByNormalizedCut(Cliques({5, 5, 5}, 1.0, {0.5, 0.05}), options);
  EXPECT_EQ(four.size(), 4u);
  for (const auto& group : four) EXPECT_GE(group.size(), 2u);
}

TEST(NormalizedCutTest, ComponentsAreSeparateAndSingletonsDropped) {
  // Two cliques with no edge between them, and an isolated node 10.
  SimilarityGraph graph = SimilarityGraph::FromEdges(11, [] {
    std::vector<WeightedEdge> edges;
    for (uint32_t a = 0; a < 5; ++a) {
      for (uint32_t b = a + 1; b < 5; ++b) {
        edges.push_back({a, b, 1.0});
        edges.push_back({a + 5, b + 5, 1.0});
      }
    }
    return edges;
  }());
  NormalizedCutStats stats;
  NormalizedCutOptions options;
  options.groups = 1;  // fewer than the components: the components stay
  EXPECT_EQ(ClusterByNormalizedCut(graph, options, &stats), Consecutive({5, 5}));
  EXPECT_EQ(stats.components, 3u);
  EXPECT_EQ(stats.dropped_nodes, 1u);
}

TEST(NormalizedCutTest, LargeGraphRecoversClustersTheSameWayOnAnyThreadCount) {
  Groups truth;
  // 8 clusters of 120 nodes: 960 nodes, the sparse solver from the first cut.
  SimilarityGraph graph = NoisyClusters(8, 120, 0.08, 400, 2, &truth);
  std::vector<Groups> results;
  std::vector<NormalizedCutStats> stats(2);
  for (int threads : {1, 2}) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
    NormalizedCutOptions options;
    options.threads = threads;
    options.spectral.seed = 11;
    results.push_back(ClusterByNormalizedCut(graph, options, &stats[threads - 1]));
  }
  EXPECT_EQ(results[0], results[1]);
  EXPECT_GT(stats[0].sparse_solves, 0u);
  EXPECT_EQ(stats[0].unconverged, 0u);
  Groups sorted_truth = truth;
  std::sort(sorted_truth.begin(), sorted_truth.end());
  EXPECT_EQ(results[0], sorted_truth);
}

}  // namespace
}  // namespace motif
