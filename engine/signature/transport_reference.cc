#include "engine/signature/transport_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/successive_shortest_path_nonnegative_weights.hpp>

#include "common/status.h"

namespace motif {
namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using FlowGraph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS, boost::no_property,
    boost::property<
        boost::edge_capacity_t, int64_t,
        boost::property<boost::edge_residual_capacity_t, int64_t,
                        boost::property<boost::edge_reverse_t, Traits::edge_descriptor,
                                        boost::property<boost::edge_weight_t, int64_t>>>>>;
using Edge = Traits::edge_descriptor;

// Adds from -> to with its zero-capacity reverse edge (weight -weight), as the algorithm needs.
Edge AddArc(FlowGraph* graph, size_t from, size_t to, int64_t capacity, int64_t weight) {
  const Edge forward = boost::add_edge(from, to, *graph).first;
  const Edge backward = boost::add_edge(to, from, *graph).first;
  boost::put(boost::edge_capacity, *graph, forward, capacity);
  boost::put(boost::edge_capacity, *graph, backward, 0);
  boost::put(boost::edge_weight, *graph, forward, weight);
  boost::put(boost::edge_weight, *graph, backward, -weight);
  boost::put(boost::edge_reverse, *graph, forward, backward);
  boost::put(boost::edge_reverse, *graph, backward, forward);
  return forward;
}

}  // namespace

void SolveTransportWithBoost(const TransportProblem& problem, TransportPlan* plan) {
  const size_t sources = problem.source_count();
  const size_t sinks = problem.sink_count();
  MOTIF_CHECK(sources > 0 && sinks > 0);
  double largest = 0;
  for (double value : problem.cost) largest = std::max(largest, value);
  const double scale = largest > 0 ? std::ldexp(1.0, 40) / largest : 0.0;

  // Vertices: super-source 0, sources 1..m, sinks m+1..m+n, super-sink m+n+1.
  const size_t super_source = 0;
  const size_t super_sink = sources + sinks + 1;
  FlowGraph graph(sources + sinks + 2);
  for (size_t source_idx = 0; source_idx < sources; ++source_idx) {
    AddArc(&graph, super_source, 1 + source_idx, problem.supply[source_idx], 0);
  }
  for (size_t sink_idx = 0; sink_idx < sinks; ++sink_idx) {
    AddArc(&graph, 1 + sources + sink_idx, super_sink, problem.demand[sink_idx], 0);
  }
  std::vector<Edge> arcs;
  arcs.reserve(sources * sinks);
  for (size_t source_idx = 0; source_idx < sources; ++source_idx) {
    for (size_t sink_idx = 0; sink_idx < sinks; ++sink_idx) {
      const int64_t weight = std::llround(problem.cost[source_idx * sinks + sink_idx] * scale);
      arcs.push_back(AddArc(&graph, 1 + source_idx, 1 + sources + sink_idx,
                            std::min(problem.supply[source_idx], problem.demand[sink_idx]),
                            weight));
    }
  }
  boost::successive_shortest_path_nonnegative_weights(graph, super_source, super_sink);

  const auto capacity = boost::get(boost::edge_capacity, graph);
  const auto residual = boost::get(boost::edge_residual_capacity, graph);
  plan->flows.clear();
  plan->cost = 0;
  plan->pivots = 0;
  for (size_t source_idx = 0; source_idx < sources; ++source_idx) {
    for (size_t sink_idx = 0; sink_idx < sinks; ++sink_idx) {
      const Edge arc = arcs[source_idx * sinks + sink_idx];
      const int64_t units = capacity[arc] - residual[arc];
      if (units == 0) continue;
      plan->flows.push_back(
          {static_cast<uint32_t>(source_idx), static_cast<uint32_t>(sink_idx), units});
      plan->cost += static_cast<double>(units) * problem.cost[source_idx * sinks + sink_idx];
    }
  }
}

}  // namespace motif
