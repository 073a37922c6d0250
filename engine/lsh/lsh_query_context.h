// LshQueryContext: what every step of an LSH query reads (the probe sequence, the bucket scans,
// the candidate verifier, the chain sweeps, the reverse pass): the archive's features, the
// trellis rules, the resolved options, the hash family and the index. LshSearch owns them all;
// a context only refers to them, so it must not outlive them. Tests build one from parts to run
// a step alone.
// Thread-safety: everything referred to is immutable; a context may be shared by all threads.
#pragma once

#include <algorithm>
#include <cstdint>

#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/hash_family.h"
#include "engine/lsh/lsh_index.h"
#include "engine/lsh/lsh_options.h"

namespace motif {

struct LshQueryContext {
  const PoseFeatures& features;
  const NeighbourRules& rules;  // clip_first_frames: the features' layout
  const LshOptions& options;    // resolved: bucket_width and hashes_per_table filled in
  const HashFamily& family;     // drawn with the options' sizes and seed
  const LshIndex& index;        // built over all of `features` with `family`
  // A full column whose k_max-th neighbour is farther than this is probed further (sparse).
  float extension_radius = 0;

  // Frames a column's query may verify: its budget, and a chained one's seeds before that. The
  // size of a query's VisitedSet (which grows past it if need be).
  uint32_t visited_capacity() const {
    if (options.chain_columns <= 1) return options.max_candidates;
    return std::max(options.max_candidates,
                    rules.k_max * (options.chain_advance + 1) + options.chained_max_candidates);
  }
};

}  // namespace motif
