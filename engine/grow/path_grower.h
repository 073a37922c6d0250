// PathGrower: the streaming tree-growing step of Meng et al. 2008 (its step 3).
// The matching trellis is fed one column at a time, in order; the grower keeps the live leaves
// of the current column (one per node, O(K)) and ONE auxiliary array of N cells, so memory is
// O(N) whatever the trellis's size, and one step costs O(K·B): O(N·K·B) in all (no sort:
// the leaves are kept in the order below as they are appended).
//
// One step, column t -> t+1 (the paper's Figure 2):
//   1. mark column t+1's nodes in the array (cell j' = the node's slot in column t+1);
//   2. each live leaf j of column t, oldest path first (root column ascending, then frame),
//      checks cells j .. j+B-1 and passes its message {root column, root frame} (the depth is
//      implied) to every marked cell it finds; a claimed cell is cleared, so each node has
//      exactly one ancestor;
//   3. a leaf that claimed nothing dies: if its path spans at least lambda columns of the top
//      row AND at least lambda matched frames, it becomes a PathCandidate (by default only the
//      longest path of each tree is kept: GrowOptions::all_branches);
//   4. column t+1's unclaimed nodes start new trees; their cells are reset (O(K)).
// Clips: frames of different clips are not consecutive. When column t+1 starts a new clip every
// path dies (the top row would cross into it), and a step j -> j' with j' in another clip than
// j is not allowed (a matched segment never spans two clips). The clip starts are permanent
// flags in the same array, so the check is O(1) per cell.
//
// Order: the paper takes column t's leaves in the trellis's row order. Taken in frame order (as
// this grower did first), a tree started a few frames above a long match claims the match's
// next nodes, and the match is cut in two where that happens: an inserted copy of a movement
// came back as two motifs, its beginning and its end (best IoU 0.25-0.46 against the copy,
// docs/design/motif_quality.md). So the oldest path claims first, the leaves kept in that order
// as they are appended (path_grower.cc, LeavesInClaimOrder; a sort each step was 35 % of the
// stage). The result is deterministic, and GrowPathsReference (reference_grower.h) follows the
// same rule.
// Thread-safety: one thread per grower.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "common/status.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/trellis_file/trellis_column.h"
#include "motifmine/defaults.h"

namespace motif {

class TrellisFileReader;

// The largest branching factor accepted: the window is checked cell by cell.
inline constexpr uint32_t kMaxBranch = 1024;

struct GrowOptions {
  // B: a path at frame j may continue to frames j .. j+B-1 of the next column. The paper's
  // experiments use 5 (its Figure 2 illustrates 3): a step breaks only when all B cells are
  // missing, probability (1-p)^B at neighbour recall p: at p = 0.9 a 200-frame path survives
  // with 99.8 % at B = 5 but 82 % at B = 3, for 5/3 the (cheap, cache-local) checks.
  uint32_t branch = motifmine::defaults::kBranch;
  // lambda: a dead path is a candidate if it spans at least this many top-row columns AND
  // this many matched frames (the paper: 60 frames at 120 fps, 0.5 s).
  uint64_t min_length = 60;
  // A tree branches, and each of its branches that dies long enough is a path of length >= lambda:
  // one tree gives many, with the same root (on real-like trellises tens per frame). By default
  // only the longest of each tree (by top length, then match length) is a candidate, the
  // paper's first clustering step done here, so that memory stays O(N + trees with a
  // candidate) instead of O(long paths). true keeps every one.
  bool all_branches = false;
};

struct GrowStats {
  uint64_t columns = 0;
  uint64_t entries = 0;           // trellis nodes visited
  uint64_t trees = 0;             // nodes with no ancestor (new roots)
  uint64_t dead_paths = 0;        // leaves that could not grow (candidates or not)
  uint64_t long_paths = 0;        // dead paths at least lambda long on both sides
  uint64_t candidates = 0;        // returned: long_paths, or one per tree that had any
  uint64_t max_column_nodes = 0;  // the largest column (live leaves held at once)
  uint64_t memory_bytes = 0;      // the grower's own at the end (PathGrower::memory_bytes)
};

// InvalidArgument unless branch is in [1, kMaxBranch] and min_length >= 1.
Status ValidateGrowOptions(const GrowOptions& options);

// InvalidArgument unless `clip_starts` is strictly increasing, starts at 0 and stays below
// frame_count (an empty list is one clip; with frame_count 0 it must be empty).
Status ValidateClipStarts(const std::vector<uint64_t>& clip_starts, uint64_t frame_count);

// Sorts candidates in the order every grower returns them: by top_start, match_start, top_end,
// match_end, then root.
void SortCandidates(std::vector<PathCandidate>* candidates);

class PathGrower {
 public:
  // frame_count N (at most 2^32), the archive's clip starts (ValidateClipStarts), options
  // (ValidateGrowOptions): InvalidArgument otherwise.
  static Result<std::unique_ptr<PathGrower>> Create(uint64_t frame_count,
                                                    const std::vector<uint64_t>& clip_starts,
                                                    const GrowOptions& options);
  ~PathGrower();

  // The column AddColumn expects next (0 first).
  uint64_t next_column() const;

  // Column next_column(): `count` nodes, frames strictly increasing and below N (the trellis
  // file's guarantee). InvalidArgument otherwise, or if all N columns were added (the grower
  // is unchanged).
  Status AddColumn(const Neighbour* nodes, size_t count);

  // After all N columns: the paths still alive die; returns every candidate, sorted
  // (SortCandidates). InvalidArgument before the last column.
  Result<std::vector<PathCandidate>> Finish();

  const GrowStats& stats() const;
  // Bytes held: the auxiliary array, the leaves of two columns and the candidates so far.
  uint64_t memory_bytes() const;

 private:
  class Impl;
  explicit PathGrower(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Streams every block of `trellis` in order (ReadBlock without distances, one block held at a
// time) through a PathGrower, giving each block's mapped pages back once grown
// (TrellisFileReader::ReleaseBlocks), so the resident set stays O(N) and not the file's size.
// `progress(done_columns, total)` after each block if given.
// Errors: those of Create (clip starts against trellis.column_count()) and of ReadBlock
// (Corruption naming the file and block).
Result<std::vector<PathCandidate>> GrowPaths(
    const TrellisFileReader& trellis, const std::vector<uint64_t>& clip_starts,
    const GrowOptions& options,
    const std::function<void(uint64_t done_columns, uint64_t total)>& progress = nullptr,
    GrowStats* stats = nullptr);

}  // namespace motif
