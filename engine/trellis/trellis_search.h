// What a trellis build and an incremental trellis update share (docs/design/algorithm.md,
// step 2): the neighbour rules of the columns, and the search that finds them, exact or by LSH,
// the LSH index built or, for an update, an earlier version's tables extended by the new frames.
// Thread-safety: pure functions; the search they make is const-safe from many threads.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "common/rank_group.h"
#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/lsh_index.h"
#include "engine/lsh/lsh_options.h"
#include "engine/lsh/lsh_search.h"

namespace motif {

// The rules of step 2 over `features`' clips (eps 0 until the radius is chosen).
NeighbourRules TrellisRules(const PoseFeatures& features, float eps, uint32_t k_max,
                            uint32_t exclusion_frames);

// The LSH tables of an earlier version of the archive: the first `frame_count` frames, hashed
// with the family `options` (all sizes resolved) draws.
struct SavedLshTables {
  uint64_t frame_count = 0;
  std::vector<LshTableEntries> tables;
  bool position_codes = false;
};

struct TrellisSearch {
  std::unique_ptr<NeighbourSearch> search;
  const LshSearch* lsh = nullptr;  // the same search when it is LSH; null for the exact one
};

// The exact search when `exact`, else LSH with `lsh` (the index shared among `ranks` when
// given). With `saved`, the index is those tables extended by the frames after them, not built
// again: `lsh` must then be resolved (hashes and width not 0). Errors of the index pass through.
Result<TrellisSearch> MakeTrellisSearch(const PoseFeatures& features, const NeighbourRules& rules,
                                        bool exact, const LshOptions& lsh, int threads,
                                        RankGroup* ranks = nullptr,
                                        SavedLshTables* saved = nullptr);

}  // namespace motif
