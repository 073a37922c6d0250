// SimilarityGraph: the sparse, symmetric, weighted graph normalized cut works on (nodes are motif
// instances). Stored as compressed rows: each undirected edge appears in both endpoints' rows,
// targets ascending. Memory O(nodes + edges); never a dense matrix.
// Thread-safety: immutable after construction.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace motif {

struct WeightedEdge {
  uint32_t a = 0;
  uint32_t b = 0;
  double weight = 0;
};

class SimilarityGraph {
 public:
  SimilarityGraph() = default;
  // Edges with a == b or weight <= 0 are ignored; a pair given twice (either order) keeps the sum
  // of its weights. Endpoints must be below node_count (checked).
  static SimilarityGraph FromEdges(uint32_t node_count, std::vector<WeightedEdge> edges);

  uint32_t node_count() const { return static_cast<uint32_t>(degrees_.size()); }
  uint64_t edge_count() const { return targets_.size() / 2; }  // undirected
  std::span<const uint32_t> Targets(uint32_t node) const {
    return {targets_.data() + offsets_[node], targets_.data() + offsets_[node + 1]};
  }
  std::span<const double> Weights(uint32_t node) const {
    return {weights_.data() + offsets_[node], weights_.data() + offsets_[node + 1]};
  }
  double Degree(uint32_t node) const { return degrees_[node]; }  // sum of the row's weights

  // Connected components, each sorted ascending, ordered by their smallest node.
  std::vector<std::vector<uint32_t>> ConnectedComponents() const;
  // The subgraph on `nodes` (ascending), renumbered 0..nodes.size()-1 in that order.
  SimilarityGraph Induced(const std::vector<uint32_t>& nodes) const;
  // Induced(part) for each of disjoint `parts` (each ascending), in one O(nodes + edges) pass.
  std::vector<SimilarityGraph> InducedParts(const std::vector<std::vector<uint32_t>>& parts) const;

 private:
  std::vector<uint64_t> offsets_{0};
  std::vector<uint32_t> targets_;
  std::vector<double> weights_;
  std::vector<double> degrees_;
};

}  // namespace motif
