// An exact solver for the transportation problem (transport_problem.h): the primal network
// simplex on the bipartite graph sources -> sinks, every arc uncapacitated (Dantzig 1951; the
// tree form and its pivoting rules as in Ahuja, Magnanti & Orlin, "Network Flows", 1993,
// chapter 11). The EMD of two signatures using all of k = 100 motifs takes about 0.4 ms of CPU
// with it, about 55 times less than Boost.Graph's successive shortest paths
// (transport_reference.h); the measurements are in docs/design/signatures.md.
//
// How it works. Masses are integers (kMassUnits), so flows are exact; costs are doubles. The
// start is the "big-M" tree: an artificial root joined to every source (arc source -> root,
// carrying its supply) and to every sink (arc root -> sink, carrying its demand, at a cost above
// any path of real arcs), after which the cheapest arc into each sink is brought in. Each pivot
// brings in the arc of most negative reduced cost within a block of whole source rows of about
// sqrt(arcs) arcs, scanned cyclically (block search), pushes flow around the cycle
// it closes and removes the blocking arc met last when the cycle is walked from its apex in the
// direction of the entering arc (Cunningham's rule: the tree stays strongly feasible, so
// degenerate pivots cannot cycle). The tree is kept as parent pointers with depths and child
// lists; a pivot re-hangs one subtree and recomputes the potentials of that subtree only.
// Arcs enter when their reduced cost is below -1e-11 times the largest cost, so the result is
// optimal to that relative precision (far below the rounding of the inputs).
// Thread-safety: Solve() uses the object's scratch buffers; use one solver per thread.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/signature/transport_problem.h"

namespace motif {

// One positive flow of a solution, by position in the problem's source and sink lists.
struct TransportFlow {
  uint32_t source = 0;
  uint32_t sink = 0;
  int64_t units = 0;
};

struct TransportPlan {
  std::vector<TransportFlow> flows;  // positive flows, by (source, sink)
  double cost = 0;                   // sum of units x cost, in cost x units
  uint64_t pivots = 0;               // simplex pivots taken (0 for the Boost reference)
};

class TransportSimplex {
 public:
  // Solves `problem` (balanced, every supply and demand > 0, costs >= 0 and finite; as built by
  // BuildTransportProblem) into `plan`. Always succeeds: a balanced problem on a complete
  // bipartite graph is feasible and bounded.
  void Solve(const TransportProblem& problem, TransportPlan* plan);

 private:
  void InitTree(const TransportProblem& problem);
  void InitialPivots();
  int64_t FindEnteringArc();
  void Pivot(int64_t arc);
  void Reroot(int32_t u_in, int32_t v_in, int32_t u_out, int64_t arc, bool arc_up,
              int64_t arc_flow);
  void UpdateSubtree(int32_t top);
  void RemoveChild(int32_t parent, int32_t child);
  void AddChild(int32_t parent, int32_t child);
  double ReducedCost(int64_t arc) const;

  // Nodes: sources 0..m-1, sinks m..m+n-1, the root m+n. Each non-root node stores its tree arc
  // to its parent: the arc id (-1: the artificial arc), its direction, flow and cost.
  int32_t sources_ = 0;
  int32_t sinks_ = 0;
  int32_t root_ = 0;
  int64_t arcs_ = 0;
  double artificial_cost_ = 0;
  double tolerance_ = 0;
  std::vector<double> cost_;      // normalised arc costs (largest = 1), source-major
  std::vector<uint8_t> in_tree_;  // per real arc
  std::vector<int32_t> parent_;
  std::vector<int64_t> pred_arc_;
  std::vector<uint8_t> pred_up_;  // 1: the tree arc points from the node to its parent
  std::vector<int64_t> pred_flow_;
  std::vector<double> pred_cost_;
  std::vector<int32_t> depth_;
  std::vector<double> potential_;
  std::vector<int32_t> first_child_;
  std::vector<int32_t> next_sibling_;
  std::vector<int32_t> prev_sibling_;
  std::vector<int32_t> stack_;
  int64_t block_size_ = 0;
  int32_t next_source_ = 0;
  uint64_t pivots_ = 0;
};

}  // namespace motif
