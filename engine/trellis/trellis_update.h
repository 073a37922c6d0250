// UpdateTrellis: the matching trellis of an archive that grew by appended clips, made from the
// trellis of its earlier version without searching the old columns again (the incremental
// half of the nightly `motifmine reindex`, docs/guide.md, "Incremental update").
//
// The archive's first N_old frames are the earlier version's (an archive only ever appends
// clips, docs/formats/frame_file.md); frames N_old .. N-1 are new. Then:
//   * the columns of the new frames are searched as a full build would (the same search over
//     the whole archive, so they are the same columns);
//   * an old column t changes only if a new frame n enters its k_max nearest. D is symmetric
//     bit for bit, so t is within eps of n exactly when n is within eps of t: the new frames'
//     own queries report the old frames they meet (NeighbourSearch::SearchColumnsAndReverse),
//     filtered by each old column's current k_max-th distance (the "thresholds": a full
//     column accepts nothing farther);
//   * each changed old column becomes the k_max nearest of its old entries and its candidates
//     (distance, then frame; FinishColumn's order). The stored distances are 16-bit codes
//     (monotone in the distance), so the order is known from the codes except among entries
//     with the code at the cut, whose exact distances are then recomputed (PoseDistance, the
//     same bits the search computed);
//   * the output is written block by block through TrellisFileWriter (resumable, renamed into
//     place at the end): a block no column of which changes is copied from the old file byte
//     for byte (AppendEncodedBlock); the others are decoded, merged and encoded again.
// With the exact search the result is byte for byte the trellis a full build with the same
// parameters writes (tests/engine/trellis/trellis_update_test.cc). With LSH the new columns
// are a full build's, and an old column gets the new frames whose queries verified it.
//
// Cost: the new columns' search (their share of a full build), one decode of the old blocks
// for the thresholds, and a decode, merge and encode of the changed blocks; memory: 4 bytes a
// column (thresholds), 12 bytes a reverse candidate, the new columns' encoded blocks.
// Thread-safety: one update per output file (the writer's lock).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "common/status.h"
#include "common/writable_file.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {

// Each column's threshold: eps if it holds fewer than k_max entries (any frame within eps
// enters it), else a little more than its k_max-th distance as stored (its 16-bit code's,
// plus twice the quantisation bound), beyond which no new frame can displace an entry.
float ColumnThreshold(const Neighbour* entries, size_t count, float eps, uint32_t k_max);

struct TrellisUpdateOptions {
  int threads = 0;  // decoding, merging and encoding blocks (0: all cores)
  FileSystem* file_system = PosixFileSystem();
  // The old trellis's column thresholds (ColumnThreshold), saved by the previous update; null:
  // computed by decoding every old block (the "thresholds" stage).
  const std::vector<float>* thresholds = nullptr;
  // Filled with the new trellis's thresholds, for the next update (left empty when the update
  // resumed an interrupted one: the blocks written before were not seen).
  std::vector<float>* next_thresholds = nullptr;
  // Called in column order with every block of the new trellis as it is written (the grower
  // streams through them here instead of reading the file again). An error stops the update.
  std::function<Status(uint64_t first_column, const std::vector<std::vector<Neighbour>>& columns)>
      on_block;
  // Stages "thresholds" (old blocks decoded), "new columns" (columns searched), "merge"
  // (output blocks written); (done, total).
  std::function<void(const std::string& stage, uint64_t done, uint64_t total)> progress;
};

struct TrellisUpdateReport {
  uint64_t old_columns = 0;
  uint64_t new_columns = 0;
  uint64_t resumed_from_column = 0;   // > 0 when an interrupted update was continued
  uint64_t reverse_candidates = 0;    // (old column, new frame) pairs within the thresholds
  uint64_t changed_columns = 0;       // old columns that gained a new neighbour
  uint64_t copied_blocks = 0;         // old blocks copied unchanged
  uint64_t rewritten_blocks = 0;      // old blocks decoded, merged and encoded again
  uint64_t new_blocks = 0;            // blocks holding new columns (the first may hold old ones)
  uint64_t exact_recomputations = 0;  // old entries whose distance was computed again (ties)
  uint64_t neighbours = 0;            // entries in the updated trellis
  SearchStats search_stats;           // of the new columns' search
  double thresholds_seconds = 0;
  double search_seconds = 0;
  double merge_seconds = 0;
};

// Writes the trellis of the whole archive to `out_path` from `previous`, its trellis over the
// first previous.column_count() frames. `features` and `search` cover the whole archive (the
// search built with `rules`); `params` are the new file's (frame_count = features.frame_count(),
// the archive's new identity). InvalidArgument if previous's eps, k_max, exclusion or weights
// differ from params', or it has more columns than the archive. Errors of the search, of the
// old file (Corruption) and of the writer (IOError, ResourceExhausted, Busy) pass through; the
// partial output file is then left for a resume by the same call.
Result<TrellisUpdateReport> UpdateTrellis(const TrellisFileReader& previous,
                                          const PoseFeatures& features, const NeighbourRules& rules,
                                          const NeighbourSearch& search,
                                          const TrellisParams& params, const std::string& out_path,
                                          const TrellisUpdateOptions& options = {});

}  // namespace motif
