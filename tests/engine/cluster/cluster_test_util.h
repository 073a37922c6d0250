// Helpers for the clustering tests: a synthetic trellis in which known motif occurrences match
// each other frame for frame (the trellis a perfect search would give for planted motifs), the
// path candidates a grower would find on it, and a small trellis writer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/trellis_file/trellis_column.h"

namespace motif::testing {

using Columns = std::vector<std::vector<Neighbour>>;

struct PlantedMotif {
  uint64_t length = 0;
  std::vector<uint64_t> starts;  // global first frames of its occurrences (disjoint)
};

// Column s_i + k of occurrence i holds frames s_j + k - 1 .. s_j + k + 1 (inside occurrence j)
// of every other occurrence j of the same motif, plus `noise` seeded random frames anywhere
// (every column, planted or not). Distances are in [0, 1].
Columns MakePlantedColumns(uint64_t frames, const std::vector<PlantedMotif>& motifs, uint32_t noise,
                           uint64_t seed);

// For every ordered pair of occurrences (i, j) of a motif: the full path (top i, matched j,
// rooted at (s_i, s_j)) and a shorter branch of the same tree.
std::vector<PathCandidate> MakePlantedCandidates(const std::vector<PlantedMotif>& motifs);

// Writes a finished trellis (eps 1, k_max = the largest column) at `path`.
Status WriteColumns(const std::string& path, const Columns& columns, uint32_t block_columns = 64);

}  // namespace motif::testing
