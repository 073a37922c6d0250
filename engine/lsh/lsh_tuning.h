// Choosing the LSH parameters left at 0 in LshOptions from the archive itself (docs/design/lsh.md,
// "Parameters").
//
// The scale that matters is how far apart, in the embedding (HashFamily), a column's neighbours
// are: that is about eps on small archives, but at a fixed eps the number of eps-neighbours grows
// linearly with N while a column keeps only k_max, so on large archives the k_max-th neighbour is
// much nearer than eps. EstimateSearchScale samples 64 frames and, on a seeded subsample of up to
// 2^17 frames of the archive, finds each one's neighbours within min(eps, its estimated k_max-th
// distance), the latter being the max(4, k_max * n / N)-th nearest of the subsample; the scale is
// the median embedding distance |e_i - e_j| of those neighbour pairs. The cost is bounded
// (~8 million distance evaluations) at any N.
// ResolveLshOptions then sets m (hashes_per_table) from N, and the cell width w from the scale:
//   m = clamp(4 + round(0.6 log2 N), 8, 24),   w = width_per_hash * m * scale_p90.
// Thread-safety: pure functions; they run on options.threads threads; deterministic for a seed.
#pragma once

#include "common/rank_group.h"
#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/lsh_options.h"

namespace motif {

struct SearchScale {
  float radius = 0;            // D units: median over sampled frames of min(eps, k_max-th distance)
  float neighbour_l2 = 0;      // embedding units: median |e_i - e_j| of the sampled neighbour pairs
  float neighbour_l2_p90 = 0;  // ... and its 90th percentile
  uint64_t neighbour_pairs = 0;  // how many pairs that median is over
};

// The scales described above. With no neighbour pair in the sample (a sparse archive or a tiny
// eps), both fall back to radius / 2.
SearchScale EstimateSearchScale(const PoseFeatures& features, const NeighbourRules& rules,
                                const LshOptions& options);
// The same, the sampled frames shared out among `ranks` (a distributed run; null: this process
// alone): the same scale on every rank. Errors: the exchange's.
Result<SearchScale> EstimateSearchScale(const PoseFeatures& features, const NeighbourRules& rules,
                                        const LshOptions& options, RankGroup* ranks);

// m for an archive of `frame_count` frames.
uint32_t DefaultHashesPerTable(uint64_t frame_count);

// `options` with hashes_per_table and bucket_width filled in where they are 0.
LshOptions ResolveLshOptions(const PoseFeatures& features, const NeighbourRules& rules,
                             const LshOptions& options);
// The same from an archive's size, weighted joint count and an already estimated scale.
LshOptions ResolveLshOptions(const LshOptions& options, uint64_t frame_count,
                             uint32_t weighted_joint_count, const SearchScale& scale);

}  // namespace motif
