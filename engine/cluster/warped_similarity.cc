#include "engine/cluster/warped_similarity.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "common/seconds_since.h"
#include "engine/distance/distance_kernel.h"
#include "engine/distance/pose_features.h"

namespace motif {

namespace {

// The cheapest warping path's mean cost over the n x m matrix `distance` (row-major, row i the
// distances of a's frame i; steps (1,0), (0,1), (1,1); ties keep the shorter path). Two rows of
// the cost and step tables at a time: the same sums in the same order as the full tables.
double MeanWarpedCost(const float* distance, uint64_t n, uint64_t m) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> cost_above(m + 1, kInf);
  std::vector<double> cost_here(m + 1, kInf);
  std::vector<uint32_t> steps_above(m + 1, 0);
  std::vector<uint32_t> steps_here(m + 1, 0);
  cost_above[0] = 0;
  for (uint64_t i = 1; i <= n; ++i) {
    cost_here[0] = kInf;
    for (uint64_t j = 1; j <= m; ++j) {
      double best_cost = cost_above[j - 1];
      uint32_t best_steps = steps_above[j - 1];
      if (cost_above[j] < best_cost) {
        best_cost = cost_above[j];
        best_steps = steps_above[j];
      }
      if (cost_here[j - 1] < best_cost) {
        best_cost = cost_here[j - 1];
        best_steps = steps_here[j - 1];
      }
      cost_here[j] = best_cost + distance[(i - 1) * m + (j - 1)];
      steps_here[j] = best_steps + 1;
    }
    std::swap(cost_above, cost_here);
    std::swap(steps_above, steps_here);
  }
  return cost_above[m] / steps_above[m];
}

// d(a, b) of every edge, in parallel. The pose distances of a pair come from the SIMD kernel,
// which gives PoseDistance's bits (distance_kernel.h), so d is MeanWarpedDistance's.
std::vector<double> EdgeDistances(const InstanceSamples& sampled,
                                  const std::vector<WeightedEdge>& edges, int threads) {
  std::vector<double> distances(edges.size());
  const DistanceKernel kernel(sampled.features);
  auto measure = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), 16), [&](const auto& range) {
      FrameBlock block_a;
      FrameBlock block_b;
      std::vector<float> matrix;
      for (size_t idx = range.begin(); idx != range.end(); ++idx) {
        const uint64_t a0 = sampled.first[edges[idx].a];
        const uint64_t a1 = sampled.first[edges[idx].a + 1];
        const uint64_t b0 = sampled.first[edges[idx].b];
        const uint64_t b1 = sampled.first[edges[idx].b + 1];
        block_a.LoadRange(sampled.features, a0, static_cast<uint32_t>(a1 - a0));
        block_b.LoadRange(sampled.features, b0, static_cast<uint32_t>(b1 - b0));
        matrix.resize((a1 - a0) * (b1 - b0));
        kernel.Compute(block_a, block_b, matrix.data(), b1 - b0);
        distances[idx] = MeanWarpedCost(matrix.data(), a1 - a0, b1 - b0);
      }
    });
  };
  if (threads > 0) {
    tbb::task_arena(threads).execute(measure);
  } else {
    measure();
  }
  return distances;
}

// Each instance's own scale: d to its k-th nearest instance that shares no frame with it (an
// overlapping one is close because it is partly the same frames); `fallback` without one.
std::vector<double> LocalScales(const std::vector<MotifInstance>& instances,
                                const std::vector<WeightedEdge>& edges,
                                const std::vector<double>& distances, uint32_t k, double fallback) {
  std::vector<std::vector<double>> near(instances.size());
  for (size_t idx = 0; idx < edges.size(); ++idx) {
    const uint32_t a = edges[idx].a;
    const uint32_t b = edges[idx].b;
    if (OverlapFrames(instances[a], instances[b]) > 0) continue;
    near[a].push_back(distances[idx]);
    near[b].push_back(distances[idx]);
  }
  std::vector<double> scales(instances.size(), fallback);
  for (size_t node = 0; node < instances.size(); ++node) {
    std::vector<double>& list = near[node];
    if (list.empty()) continue;
    std::sort(list.begin(), list.end());
    // A floor: two identical instances would make a zero scale.
    scales[node] = std::max(list[std::min<size_t>(k, list.size()) - 1], 1e-6);
  }
  return scales;
}

}  // namespace

double MeanWarpedDistance(const PoseFeatures& features, uint64_t a0, uint64_t a1, uint64_t b0,
                          uint64_t b1) {
  const uint64_t m = b1 - b0;
  std::vector<float> matrix((a1 - a0) * m);
  for (uint64_t i = 0; i < a1 - a0; ++i) {
    for (uint64_t j = 0; j < m; ++j) matrix[i * m + j] = PoseDistance(features, a0 + i, b0 + j);
  }
  return MeanWarpedCost(matrix.data(), a1 - a0, m);
}

Result<std::vector<double>> WarpedDistances(const FrameFileReader& archive,
                                            const std::vector<MotifInstance>& instances,
                                            const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                                            uint32_t samples, int threads) {
  if (pairs.empty()) return std::vector<double>();
  // Only the instances of some pair are sampled, in id order.
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> sampled_idx(instances.size(), kUnused);
  for (const auto& [a, b] : pairs) {
    if (a >= instances.size() || b >= instances.size()) {
      return Status::InvalidArgument("warped distance: a pair names no instance");
    }
    sampled_idx[a] = sampled_idx[b] = 0;
  }
  std::vector<MotifInstance> used;
  for (size_t id = 0; id < instances.size(); ++id) {
    if (sampled_idx[id] == kUnused) continue;
    sampled_idx[id] = static_cast<uint32_t>(used.size());
    used.push_back(instances[id]);
  }
  MOTIF_ASSIGN_OR_RETURN(const InstanceSamples sampled,
                         ReadInstanceSamples(archive, used, std::max(samples, 2u), 0, threads));
  std::vector<std::pair<uint32_t, uint32_t>> renumbered;
  renumbered.reserve(pairs.size());
  for (const auto& [a, b] : pairs) renumbered.emplace_back(sampled_idx[a], sampled_idx[b]);
  return WarpedDistances(sampled, renumbered, threads);
}

Result<std::vector<double>> WarpedDistances(const InstanceSamples& samples,
                                            const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                                            int threads) {
  std::vector<WeightedEdge> edges;
  edges.reserve(pairs.size());
  for (const auto& [a, b] : pairs) {
    if (a + 1 >= samples.first.size() || b + 1 >= samples.first.size()) {
      return Status::InvalidArgument("warped distance: a pair names no instance");
    }
    edges.push_back({a, b, 0.0});
  }
  return EdgeDistances(samples, edges, threads);
}

Result<SimilarityGraph> ReweightByWarpedDistance(const FrameFileReader& archive,
                                                 const std::vector<MotifInstance>& instances,
                                                 const SimilarityGraph& graph, float eps,
                                                 const WarpedSimilarityOptions& options,
                                                 WarpedSimilarityStats* stats) {
  if (!options.enabled || graph.edge_count() == 0) return graph;  // nothing to read
  const auto started = std::chrono::steady_clock::now();
  MOTIF_ASSIGN_OR_RETURN(
      const InstanceSamples samples,
      ReadInstanceSamples(archive, instances, std::max(options.samples, 2u), eps, options.threads));
  MOTIF_ASSIGN_OR_RETURN(SimilarityGraph reweighted,
                         ReweightByWarpedDistance(samples, instances, graph, eps, options, stats));
  if (stats != nullptr) stats->seconds = SecondsSince(started);  // the reading included
  return reweighted;
}

Result<SimilarityGraph> ReweightByWarpedDistance(const InstanceSamples& samples,
                                                 const std::vector<MotifInstance>& instances,
                                                 const SimilarityGraph& graph, float eps,
                                                 const WarpedSimilarityOptions& options,
                                                 WarpedSimilarityStats* stats) {
  const auto started = std::chrono::steady_clock::now();
  if (!options.enabled || graph.edge_count() == 0) return graph;
  if (options.neighbours == 0) {
    return Status::InvalidArgument("warped similarity: the local scale needs neighbours >= 1");
  }
  if (graph.node_count() != instances.size() || samples.first.size() != instances.size() + 1) {
    return Status::InvalidArgument("warped similarity: the graph's nodes are not the instances");
  }
  std::vector<WeightedEdge> edges;
  edges.reserve(graph.edge_count());
  for (uint32_t a = 0; a < graph.node_count(); ++a) {
    for (uint32_t b : graph.Targets(a)) {
      if (b > a) edges.push_back({a, b, 0.0});
    }
  }
  const std::vector<double> distances = EdgeDistances(samples, edges, options.threads);
  std::vector<double> scales =
      LocalScales(instances, edges, distances, options.neighbours, options.fallback_scale * eps);
  for (double& scale : scales) scale = std::max(scale, options.floor_scale * eps);  // noise
  const double max_squared = options.max_scales * options.max_scales;
  uint64_t dropped = 0;
  for (size_t idx = 0; idx < edges.size(); ++idx) {
    const double squared =
        distances[idx] * distances[idx] / (scales[edges[idx].a] * scales[edges[idx].b]);
    // FromEdges drops a weight of 0; a floor keeps every other edge an edge.
    const bool far = squared > max_squared;
    dropped += far ? 1 : 0;
    edges[idx].weight = far ? 0.0 : std::max(std::exp(-squared), 1e-12);
  }
  if (stats != nullptr) {
    stats->edges = edges.size();
    stats->dropped_edges = dropped;
    double total = 0;
    for (double distance : distances) total += distance;
    stats->mean_distance = total / static_cast<double>(edges.size());
    stats->seconds = SecondsSince(started);
  }
  return SimilarityGraph::FromEdges(graph.node_count(), std::move(edges));
}

}  // namespace motif
