#include "engine/cluster/similarity_graph.h"

#include <algorithm>
#include <limits>

#include "common/status.h"

namespace motif {

SimilarityGraph SimilarityGraph::FromEdges(uint32_t node_count, std::vector<WeightedEdge> edges) {
  std::vector<WeightedEdge> directed;
  directed.reserve(2 * edges.size());
  for (const WeightedEdge& edge : edges) {
    MOTIF_CHECK(edge.a < node_count && edge.b < node_count);
    if (edge.a == edge.b || !(edge.weight > 0)) continue;
    directed.push_back(edge);
    directed.push_back({edge.b, edge.a, edge.weight});
  }
  edges.clear();
  edges.shrink_to_fit();
  // Stable: duplicates are then summed in input order, whatever the sort does.
  std::stable_sort(directed.begin(), directed.end(),
                   [](const WeightedEdge& x, const WeightedEdge& y) {
                     return x.a != y.a ? x.a < y.a : x.b < y.b;
                   });
  SimilarityGraph graph;
  graph.offsets_.assign(static_cast<size_t>(node_count) + 1, 0);
  graph.degrees_.assign(node_count, 0.0);
  for (size_t idx = 0; idx < directed.size();) {
    const WeightedEdge& first = directed[idx];
    double weight = 0;
    size_t next = idx;
    // Duplicates are adjacent after sorting; summing them in sorted order keeps this exact and
    // symmetric (both directions see the same addends in the same order).
    while (next < directed.size() && directed[next].a == first.a && directed[next].b == first.b) {
      weight += directed[next].weight;
      ++next;
    }
    graph.targets_.push_back(first.b);
    graph.weights_.push_back(weight);
    ++graph.offsets_[first.a + 1];
    idx = next;
  }
  for (uint32_t node = 0; node < node_count; ++node) {
    graph.offsets_[node + 1] += graph.offsets_[node];
  }
  for (uint32_t node = 0; node < node_count; ++node) {
    double degree = 0;
    for (double weight : graph.Weights(node)) degree += weight;
    graph.degrees_[node] = degree;
  }
  return graph;
}

std::vector<std::vector<uint32_t>> SimilarityGraph::ConnectedComponents() const {
  constexpr uint32_t kUnseen = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> component_of(node_count(), kUnseen);
  std::vector<std::vector<uint32_t>> components;
  std::vector<uint32_t> stack;
  for (uint32_t seed = 0; seed < node_count(); ++seed) {
    if (component_of[seed] != kUnseen) continue;
    const uint32_t component = static_cast<uint32_t>(components.size());
    components.emplace_back();
    component_of[seed] = component;
    stack.push_back(seed);
    while (!stack.empty()) {
      const uint32_t node = stack.back();
      stack.pop_back();
      components.back().push_back(node);
      for (uint32_t target : Targets(node)) {
        if (component_of[target] == kUnseen) {
          component_of[target] = component;
          stack.push_back(target);
        }
      }
    }
    std::sort(components.back().begin(), components.back().end());
  }
  return components;
}

SimilarityGraph SimilarityGraph::Induced(const std::vector<uint32_t>& nodes) const {
  return std::move(InducedParts({nodes}).front());
}

std::vector<SimilarityGraph> SimilarityGraph::InducedParts(
    const std::vector<std::vector<uint32_t>>& parts) const {
  constexpr uint32_t kOutside = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> part_of(node_count(), kOutside);
  std::vector<uint32_t> local(node_count(), 0);
  for (size_t part = 0; part < parts.size(); ++part) {
    for (size_t idx = 0; idx < parts[part].size(); ++idx) {
      MOTIF_CHECK(part_of[parts[part][idx]] == kOutside);
      part_of[parts[part][idx]] = static_cast<uint32_t>(part);
      local[parts[part][idx]] = static_cast<uint32_t>(idx);
    }
  }
  std::vector<SimilarityGraph> graphs(parts.size());
  for (size_t part = 0; part < parts.size(); ++part) {
    const std::vector<uint32_t>& nodes = parts[part];
    SimilarityGraph& graph = graphs[part];
    graph.offsets_.assign(nodes.size() + 1, 0);
    graph.degrees_.assign(nodes.size(), 0.0);
    for (size_t idx = 0; idx < nodes.size(); ++idx) {
      std::span<const uint32_t> targets = Targets(nodes[idx]);
      std::span<const double> weights = Weights(nodes[idx]);
      double degree = 0;
      for (size_t edge = 0; edge < targets.size(); ++edge) {
        if (part_of[targets[edge]] != part) continue;
        graph.targets_.push_back(local[targets[edge]]);  // ascending: `nodes` is ascending
        graph.weights_.push_back(weights[edge]);
        degree += weights[edge];
      }
      graph.offsets_[idx + 1] = graph.targets_.size();
      graph.degrees_[idx] = degree;
    }
  }
  return graphs;
}

}  // namespace motif
