// Helpers shared by the path grower tests: hand-built trellises (columns of frames), growing
// them in memory or through a trellis file, and seeded random trellises shaped like real ones
// (diagonal runs of similar frames, time warps, noise nodes).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/grow/path_grower.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/trellis_file/trellis_column.h"

namespace motif {
// gtest prints candidates as "top [a, b) match [c, d) root (e, f)".
void PrintTo(const PathCandidate& candidate, std::ostream* out);
}  // namespace motif

namespace motif::testing {

using GrowColumns = std::vector<std::vector<Neighbour>>;

// N empty columns.
GrowColumns EmptyColumns(uint64_t frame_count);
// Adds frame `frame` to column `column` (kept sorted, no duplicates).
void AddNode(GrowColumns* columns, uint64_t column, uint64_t frame);
// Adds the nodes (first_column + i, frames[i]).
void AddPath(GrowColumns* columns, uint64_t first_column, const std::vector<uint64_t>& frames);
// Adds the diagonal (first_column + i, first_frame + i) for i < length.
void AddDiagonal(GrowColumns* columns, uint64_t first_column, uint64_t first_frame,
                 uint64_t length);

// Streams the columns through a PathGrower.
Result<std::vector<PathCandidate>> GrowInMemory(const GrowColumns& columns,
                                                const std::vector<uint64_t>& clip_starts,
                                                const GrowOptions& options);
// Writes the columns as a trellis file in blocks of `block_columns` and grows it with GrowPaths.
Result<std::vector<PathCandidate>> GrowThroughFile(const std::string& path,
                                                   const GrowColumns& columns,
                                                   const std::vector<uint64_t>& clip_starts,
                                                   const GrowOptions& options,
                                                   uint32_t block_columns = 64);
// Writes the columns as a trellis file (k_max = the largest column, at least 1).
Status WriteColumns(const std::string& path, const GrowColumns& columns,
                    uint32_t block_columns = 64);

// A candidate from its two ranges, rooted at their starts (what the growers produce).
PathCandidate Candidate(uint64_t top_start, uint64_t top_end, uint64_t match_start,
                        uint64_t match_end);

// A random trellis of `frame_count` columns: `paths` planted paths (random start, length, speed
// changes within [0, max_step] frames a column), `noise` random nodes a column, and random
// short runs; with clips starting at `clip_starts`. Deterministic in `seed`.
GrowColumns RandomColumns(uint64_t frame_count, uint64_t seed, int paths, int noise,
                          uint32_t max_step);
// Random clip starts: 0, then `count - 1` distinct frames.
std::vector<uint64_t> RandomClipStarts(uint64_t frame_count, uint64_t seed, int count);

// Writes a synthetic archive of `frames` frames (clips of 10 to 20 s at 120 fps, two motifs
// planted three times each) at `path`.
Status WriteSynthArchive(const std::string& path, uint64_t frames, uint64_t seed);

std::string Describe(const std::vector<PathCandidate>& candidates);

}  // namespace motif::testing
