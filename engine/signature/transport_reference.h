// A reference solver for the transportation problem (transport_problem.h): Boost.Graph's
// successive shortest paths (successive_shortest_path_nonnegative_weights) on the network
// super-source -> sources -> sinks -> super-sink. It is exact and independent of our network
// simplex (transport_simplex.h), which the tests check against it on random problems; it is too
// slow to build signature matrices with (docs/design/signatures.md, section 1.3).
//
// Boost's Dijkstra throws on a negative edge weight, and with floating-point costs the reduced
// weights w + d(u) - d(v) of successive shortest paths can come out slightly negative by rounding.
// So the costs are rounded to integers first, scaled so the largest is 2^40: the flows it returns
// are optimal for costs within 2^-41 (relative to the largest) of the given ones, and the cost it
// reports is computed from the given costs.
// Thread-safety: a pure function.
#pragma once

#include "engine/signature/transport_problem.h"
#include "engine/signature/transport_simplex.h"

namespace motif {

// Solves `problem` (as built by BuildTransportProblem) into `plan` (pivots = 0).
void SolveTransportWithBoost(const TransportProblem& problem, TransportPlan* plan);

}  // namespace motif
