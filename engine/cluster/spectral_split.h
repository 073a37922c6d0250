// The two-way normalized cut of Shi & Malik (2000) on one connected similarity graph: the
// generalized eigenvector y of (D − W) y = λ D y for the second smallest λ relaxes the minimum
// Ncut(A, B) = cut(A, B) / assoc(A, V) + cut(A, B) / assoc(B, V); the partition is then the best
// of the threshold cuts along y. We evaluate every threshold exactly (a sweep over the nodes in
// order of y, updating cut and assoc in O(edges) in all), not just a few sampled ones.
//
// y = D^(-1/2) v, v the eigenvector of the second largest eigenvalue of N = D^(-1/2) W D^(-1/2).
// Small graphs: dense self-adjoint eigensolver (Eigen). Large graphs: implicitly restarted
// Lanczos (Spectra) on N − 3·v1·v1ᵀ, v1 = D^(1/2)·1 normalised (N's top eigenvector, eigenvalue
// 1, is moved to −2, below N's spectrum, so the largest remaining eigenvalue is the second);
// only products with the sparse W are needed, and its starting vector is drawn from the seed.
// Both paths are deterministic: the same graph gives the same vector on any thread count.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "engine/cluster/similarity_graph.h"

namespace motif {

struct SpectralOptions {
  uint32_t dense_max_nodes = 96;  // above: the sparse Lanczos solver (dense is O(n^3))
  uint64_t seed = 1;              // the Lanczos starting vector
};

struct FiedlerVector {
  std::vector<double> values;  // y, one per node; empty if the solver did not converge
  double eigenvalue = 0;       // λ2 of the normalized Laplacian I − N
  bool sparse = false;         // solved with Lanczos
};

// The relaxed Ncut indicator y of a connected graph with at least 2 nodes (every degree > 0).
FiedlerVector ComputeFiedlerVector(const SimilarityGraph& graph, const SpectralOptions& options);

struct TwoWayCut {
  double ncut = std::numeric_limits<double>::infinity();  // infinity: no admissible cut
  std::vector<uint32_t> side_a;                           // ascending
  std::vector<uint32_t> side_b;                           // ascending
};

// The threshold cut along `values` (nodes ordered by value, then id) with the smallest Ncut and
// at least `min_side` nodes on each side.
TwoWayCut BestSweepCut(const SimilarityGraph& graph, const std::vector<double>& values,
                       uint32_t min_side);

// Ncut(A, V \ A) of the partition given by `in_a` (for tests and reports).
double NormalizedCutValue(const SimilarityGraph& graph, const std::vector<bool>& in_a);

}  // namespace motif
