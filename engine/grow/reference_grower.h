// GrowPathsReference: the O(N·K²) pairwise path grower, the baseline the paper improves on
// ([YWM*07]): for each pair of adjacent columns it compares every node of column t with every
// node of column t+1 (|j' - j| within the branch window) instead of using the auxiliary array.
// It applies the same rules as PathGrower (path_grower.h) in the same order, so it returns
// exactly the same candidates on any input: a test oracle and a benchmark baseline. It may hold
// the whole trellis in memory.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/grow/path_grower.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/trellis_file/trellis_column.h"

namespace motif {

class TrellisFileReader;

// `columns` holds the N columns (frames strictly increasing, below N). InvalidArgument as
// PathGrower. Candidates sorted (SortCandidates).
Result<std::vector<PathCandidate>> GrowPathsReference(
    const std::vector<std::vector<Neighbour>>& columns, const std::vector<uint64_t>& clip_starts,
    const GrowOptions& options, GrowStats* stats = nullptr);

// Reads every column of `trellis` into memory, then as above.
Result<std::vector<PathCandidate>> GrowPathsReference(const TrellisFileReader& trellis,
                                                      const std::vector<uint64_t>& clip_starts,
                                                      const GrowOptions& options,
                                                      GrowStats* stats = nullptr);

}  // namespace motif
