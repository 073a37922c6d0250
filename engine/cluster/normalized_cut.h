// Clustering a similarity graph into motifs by normalized cut (Shi & Malik 2000), recursively.
//
// Connected components come first: instances that share nothing are different motifs, so each
// component is a group before any eigenvector is computed. A group is then cut in two by the
// spectral two-way cut (spectral_split.h); a group whose subgraph falls apart is split into its
// components (Ncut 0).
//
// How many groups (G):
//  * automatic (groups = 0): a group is cut while its best two-way cut has Ncut below
//    `max_ncut`. Ncut ranges over [0, 2]: two motifs joined by a few weak edges cut near 0, a
//    motif whose instances all resemble each other (a near-clique) cuts near 1 whichever way.
//    The default 0.5 stops there, so no motif is split for being large, and a split means each
//    side keeps most of its association inside (Shi & Malik's own recursive scheme, with their
//    Ncut threshold as the stopping rule). We chose this over the eigengap of the normalized
//    Laplacian because it needs only the second eigenvector of each group (the sparse solver
//    cost stays O(edges) per Lanczos step whatever G is, where the eigengap needs the first G of
//    an unknown G), and because it has no k-means step and so no seeding.
//  * given G: starting from the components, the group whose best cut has the smallest Ncut is
//    cut, until there are G groups or no group can be cut. More components than G are kept
//    (instances with no similarity cannot be merged); fewer than G is reached by cutting.
// No cut leaves a side smaller than `min_group_size`; groups smaller than it are dropped (a motif
// needs two instances). Groups are cut in parallel (TBB) level by level, and every choice is
// ordered by values and node ids, so the result does not depend on the thread count.
// Thread-safety: pure function.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/cluster/similarity_graph.h"
#include "engine/cluster/spectral_split.h"
#include "motifmine/defaults.h"

namespace motif {

struct NormalizedCutOptions {
  uint32_t groups = 0;  // 0: automatic
  double max_ncut =
      motifmine::defaults::kMaxNcut;  // automatic: cut while the best cut's Ncut is below this
  uint32_t min_group_size = 2;
  SpectralOptions spectral;
  int threads = 0;  // 0: all cores
};

struct NormalizedCutStats {
  uint64_t components = 0;     // connected components of the whole graph
  uint64_t spectral_cuts = 0;  // two-way cuts applied
  uint64_t eigen_solves = 0;
  uint64_t sparse_solves = 0;  // of which Lanczos
  uint64_t unconverged = 0;    // Lanczos gave up: that group was left whole
  uint64_t dropped_nodes = 0;  // in groups smaller than min_group_size
};

// The groups (each ascending), ordered by smallest node.
std::vector<std::vector<uint32_t>> ClusterByNormalizedCut(const SimilarityGraph& graph,
                                                          const NormalizedCutOptions& options,
                                                          NormalizedCutStats* stats = nullptr);

}  // namespace motif
