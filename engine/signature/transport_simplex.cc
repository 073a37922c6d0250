#include "engine/signature/transport_simplex.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/status.h"

namespace motif {

void TransportSimplex::Solve(const TransportProblem& problem, TransportPlan* plan) {
  MOTIF_CHECK(problem.source_count() > 0 && problem.sink_count() > 0);
  MOTIF_CHECK(problem.cost.size() == problem.source_count() * problem.sink_count());
  InitTree(problem);
  InitialPivots();
  // Strongly feasible trees make the simplex finite; this bound only turns a numerical surprise
  // into a crash with a message instead of a hang.
  const uint64_t pivot_limit = 1000 + 100 * static_cast<uint64_t>(arcs_ + root_);
  for (;;) {
    const int64_t arc = FindEnteringArc();
    if (arc < 0) break;
    Pivot(arc);
    MOTIF_CHECK(pivots_ < pivot_limit);
  }

  plan->flows.clear();
  plan->cost = 0;
  plan->pivots = pivots_;
  for (int32_t node = 0; node < root_; ++node) {
    if (pred_flow_[node] == 0) continue;
    // A feasible problem leaves no flow on the artificial arcs (their cost exceeds any path).
    MOTIF_CHECK(pred_arc_[node] >= 0);
    const int64_t arc = pred_arc_[node];
    plan->flows.push_back({static_cast<uint32_t>(arc / sinks_), static_cast<uint32_t>(arc % sinks_),
                           pred_flow_[node]});
  }
  std::sort(plan->flows.begin(), plan->flows.end(),
            [](const TransportFlow& a, const TransportFlow& b) {
              return a.source != b.source ? a.source < b.source : a.sink < b.sink;
            });
  for (const TransportFlow& flow : plan->flows) {
    plan->cost += static_cast<double>(flow.units) *
                  problem.cost[static_cast<size_t>(flow.source) * sinks_ + flow.sink];
  }
}

void TransportSimplex::InitTree(const TransportProblem& problem) {
  sources_ = static_cast<int32_t>(problem.source_count());
  sinks_ = static_cast<int32_t>(problem.sink_count());
  root_ = sources_ + sinks_;
  arcs_ = static_cast<int64_t>(sources_) * sinks_;
  const int32_t nodes = root_ + 1;

  // Costs are scaled so the largest is 1: the tolerance and the artificial cost are then fixed
  // numbers, whatever the units of the ground distance.
  double largest = 0;
  for (double value : problem.cost) largest = std::max(largest, value);
  const double scale = largest > 0 ? 1.0 / largest : 1.0;
  cost_.resize(static_cast<size_t>(arcs_));
  for (int64_t arc = 0; arc < arcs_; ++arc) cost_[arc] = problem.cost[arc] * scale;
  // A simple path of real arcs has at most nodes - 1 arcs of cost <= 1.
  artificial_cost_ = static_cast<double>(nodes) + 1.0;
  tolerance_ = 1e-11;
  in_tree_.assign(static_cast<size_t>(arcs_), 0);

  parent_.assign(nodes, root_);
  pred_arc_.assign(nodes, -1);
  pred_up_.assign(nodes, 0);
  pred_flow_.assign(nodes, 0);
  pred_cost_.assign(nodes, 0.0);
  depth_.assign(nodes, 1);
  potential_.assign(nodes, 0.0);
  first_child_.assign(nodes, -1);
  next_sibling_.assign(nodes, -1);
  prev_sibling_.assign(nodes, -1);
  parent_[root_] = -1;
  depth_[root_] = 0;
  // Sources send their supply up to the root at no cost; the root sends each sink its demand at
  // the artificial cost. Every arc carries a positive flow: the tree is strongly feasible.
  for (int32_t source = 0; source < sources_; ++source) {
    pred_up_[source] = 1;
    pred_flow_[source] = problem.supply[source];
    AddChild(root_, source);
  }
  for (int32_t sink = 0; sink < sinks_; ++sink) {
    const int32_t node = sources_ + sink;
    pred_flow_[node] = problem.demand[sink];
    pred_cost_[node] = artificial_cost_;
    potential_[node] = artificial_cost_;
    AddChild(root_, node);
  }
  block_size_ = std::min<int64_t>(
      arcs_, std::max<int64_t>(10, static_cast<int64_t>(std::ceil(std::sqrt(arcs_)))));
  next_source_ = 0;
  pivots_ = 0;
}

// The cheapest arc into each sink, brought in first: a cheap approximation of the optimum that
// saves many block-search pivots.
void TransportSimplex::InitialPivots() {
  for (int32_t sink = 0; sink < sinks_; ++sink) {
    int64_t best_arc = sink;
    for (int32_t source = 1; source < sources_; ++source) {
      const int64_t arc = static_cast<int64_t>(source) * sinks_ + sink;
      if (cost_[arc] < cost_[best_arc]) best_arc = arc;
    }
    if (!in_tree_[best_arc] && ReducedCost(best_arc) < -tolerance_) Pivot(best_arc);
  }
}

double TransportSimplex::ReducedCost(int64_t arc) const {
  return cost_[arc] + potential_[arc / sinks_] - potential_[sources_ + arc % sinks_];
}

// Block search, a block being whole rows of sources (about sqrt(arcs) arcs, at least 10): the
// most negative reduced cost within the first block that has one. Tree arcs need no test: their
// reduced cost is 0 up to the rounding of the potentials, far inside the tolerance.
int64_t TransportSimplex::FindEnteringArc() {
  double best = -tolerance_;
  int64_t best_arc = -1;
  int32_t source = next_source_;
  int64_t in_block = 0;
  const double* sink_potential = &potential_[sources_];
  for (int32_t scanned = 0; scanned < sources_; ++scanned) {
    const double* row_cost = &cost_[static_cast<size_t>(source) * sinks_];
    const double source_potential = potential_[source];
    double row_best = best;
    int32_t row_best_sink = -1;
    for (int32_t sink = 0; sink < sinks_; ++sink) {
      const double reduced = row_cost[sink] + source_potential - sink_potential[sink];
      if (reduced < row_best) {
        row_best = reduced;
        row_best_sink = sink;
      }
    }
    if (row_best_sink >= 0) {
      best = row_best;
      best_arc = static_cast<int64_t>(source) * sinks_ + row_best_sink;
    }
    if (++source == sources_) source = 0;
    in_block += sinks_;
    if (in_block >= block_size_) {
      if (best_arc >= 0) break;
      in_block = 0;
    }
  }
  next_source_ = source;
  MOTIF_CHECK(best_arc < 0 || !in_tree_[best_arc]);
  return best_arc;
}

void TransportSimplex::Pivot(int64_t arc) {
  const int32_t s = static_cast<int32_t>(arc / sinks_);
  const int32_t t = sources_ + static_cast<int32_t>(arc % sinks_);
  // The apex of the cycle the arc closes.
  int32_t x = s;
  int32_t y = t;
  while (x != y) {
    if (depth_[x] > depth_[y]) {
      x = parent_[x];
    } else if (depth_[y] > depth_[x]) {
      y = parent_[y];
    } else {
      x = parent_[x];
      y = parent_[y];
    }
  }
  const int32_t join = x;

  // Flow goes around the cycle join -> ... -> s -> t -> ... -> join. It decreases on the tree
  // arcs walked against their direction: upward arcs on the s side, downward arcs on the t side.
  // Cunningham's rule takes the blocking arc met last on that walk: on the s side the one nearest
  // s (strict <, walking up from s), on the t side the one nearest the apex (<=, walking up from
  // t), and the t side over the s side.
  int64_t delta = std::numeric_limits<int64_t>::max();
  int32_t u_out = -1;
  bool out_on_source_side = false;
  for (int32_t node = s; node != join; node = parent_[node]) {
    if (pred_up_[node] && pred_flow_[node] < delta) {
      delta = pred_flow_[node];
      u_out = node;
      out_on_source_side = true;
    }
  }
  for (int32_t node = t; node != join; node = parent_[node]) {
    if (!pred_up_[node] && pred_flow_[node] <= delta) {
      delta = pred_flow_[node];
      u_out = node;
      out_on_source_side = false;
    }
  }
  MOTIF_CHECK(u_out >= 0);  // the graph has no directed cycle, so some arc blocks
  if (delta > 0) {
    for (int32_t node = s; node != join; node = parent_[node]) {
      pred_flow_[node] += pred_up_[node] ? -delta : delta;
    }
    for (int32_t node = t; node != join; node = parent_[node]) {
      pred_flow_[node] += pred_up_[node] ? delta : -delta;
    }
  }

  if (pred_arc_[u_out] >= 0) in_tree_[pred_arc_[u_out]] = 0;
  in_tree_[arc] = 1;
  // The subtree cut off below u_out holds the entering arc's endpoint on the leaving side.
  const int32_t u_in = out_on_source_side ? s : t;
  const int32_t v_in = out_on_source_side ? t : s;
  Reroot(u_in, v_in, u_out, arc, /*arc_up=*/u_in == s, delta);
  UpdateSubtree(u_in);
  ++pivots_;
}

// Hangs the subtree that was below u_out from v_in by the entering arc, re-rooted at u_in: the
// parent links on the path u_in .. u_out (the stem) are reversed, each tree arc moving one node
// down the path with its direction seen from the other end.
void TransportSimplex::Reroot(int32_t u_in, int32_t v_in, int32_t u_out, int64_t arc, bool arc_up,
                              int64_t arc_flow) {
  int32_t node = u_in;
  int32_t new_parent = v_in;
  int64_t new_arc = arc;
  uint8_t new_up = arc_up ? 1 : 0;
  int64_t new_flow = arc_flow;
  double new_cost = cost_[arc];
  for (;;) {
    const int32_t old_parent = parent_[node];
    const int64_t old_arc = pred_arc_[node];
    const uint8_t old_up = pred_up_[node];
    const int64_t old_flow = pred_flow_[node];
    const double old_cost = pred_cost_[node];
    RemoveChild(old_parent, node);
    parent_[node] = new_parent;
    pred_arc_[node] = new_arc;
    pred_up_[node] = new_up;
    pred_flow_[node] = new_flow;
    pred_cost_[node] = new_cost;
    AddChild(new_parent, node);
    if (node == u_out) break;
    new_parent = node;
    new_arc = old_arc;
    new_up = old_up ? 0 : 1;
    new_flow = old_flow;
    new_cost = old_cost;
    node = old_parent;
  }
}

// Depths and potentials of the subtree under `top`, from its (new) parent down. A tree arc has
// reduced cost 0: cost + potential(tail) - potential(head) = 0.
void TransportSimplex::UpdateSubtree(int32_t top) {
  stack_.clear();
  stack_.push_back(top);
  while (!stack_.empty()) {
    const int32_t node = stack_.back();
    stack_.pop_back();
    const int32_t parent = parent_[node];
    depth_[node] = depth_[parent] + 1;
    potential_[node] = pred_up_[node] ? potential_[parent] - pred_cost_[node]
                                      : potential_[parent] + pred_cost_[node];
    for (int32_t child = first_child_[node]; child >= 0; child = next_sibling_[child]) {
      stack_.push_back(child);
    }
  }
}

void TransportSimplex::RemoveChild(int32_t parent, int32_t child) {
  const int32_t prev = prev_sibling_[child];
  const int32_t next = next_sibling_[child];
  if (prev >= 0) {
    next_sibling_[prev] = next;
  } else {
    first_child_[parent] = next;
  }
  if (next >= 0) prev_sibling_[next] = prev;
  prev_sibling_[child] = -1;
  next_sibling_[child] = -1;
}

void TransportSimplex::AddChild(int32_t parent, int32_t child) {
  prev_sibling_[child] = -1;
  next_sibling_[child] = first_child_[parent];
  if (first_child_[parent] >= 0) prev_sibling_[first_child_[parent]] = child;
  first_child_[parent] = child;
}

}  // namespace motif
