// ExactSearch: the trellis columns by blocked brute force, every query frame against all N
// frames of the archive with the block kernel (distance_kernel.h): O(N^2) distance evaluations,
// the baseline the LSH search (engine/lsh) is measured against, both for speed and for recall.
// The column rules are NeighbourRules' (neighbour_search.h): D <= eps, not the frame itself nor
// a frame of the same clip closer than exclusion_frames; the k_max nearest kept (ties: lower
// frame first), then sorted by frame.
//
// Work is split into blocks of query frames, run in parallel (TBB, inside a task_arena of
// `threads` threads); each task computes its queries against the archive one candidate block
// at a time and writes only its own columns and its own statistics slot. Every distance is the
// scalar PoseDistance bit for bit, so the columns are identical for any thread count and block
// size, and identical to a direct double loop over PoseDistance.
//
// Memory: per running task, one candidate block and one query-by-candidate distance tile
// (query_block_frames * candidate_block_frames floats, 256 KB by default), plus its columns.
// Thread-safety: SearchColumns is const and safe from many threads on disjoint outputs; the
// PoseFeatures must outlive the search.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"

namespace motif {

struct ExactSearchOptions {
  uint32_t threads = 0;                   // 0: all cores
  uint32_t query_block_frames = 256;      // queries per task (also the unit of parallelism)
  uint32_t candidate_block_frames = 256;  // candidates dequantised and compared at once
};

class ExactSearch : public NeighbourSearch {
 public:
  // `rules.clip_first_frames` may be left empty: the archive's clips are used. If given, it
  // must be ascending and start with 0 (checked by SearchColumns).
  ExactSearch(const PoseFeatures& features, NeighbourRules rules, ExactSearchOptions options = {});

  // Fills (*columns)[i] with column first_column + i for i < count (columns is resized to
  // `count` if it is smaller) and adds to *stats: columns, distance_evaluations (count * N),
  // neighbours kept, capped_columns. InvalidArgument if the range leaves the archive, if the
  // archive has 2^32 frames or more (Neighbour::frame is 32-bit), if eps is negative or not
  // finite, or if the clip list is malformed.
  Status SearchColumns(uint64_t first_column, uint64_t count,
                       std::vector<std::vector<Neighbour>>* columns,
                       SearchStats* stats) const override;
  // Every frame below query.frame_limit within eps and its threshold (NeighbourSearch).
  Status SearchColumnsAndReverse(uint64_t first_column, uint64_t count, const ReverseQuery& query,
                                 std::vector<std::vector<Neighbour>>* columns,
                                 std::vector<std::vector<Neighbour>>* reverse,
                                 SearchStats* stats) const override;

  const NeighbourRules& rules() const { return rules_; }
  const ExactSearchOptions& options() const { return options_; }

 private:
  // Both searches; `query` and `reverse` null for the columns alone.
  Status Search(uint64_t first_column, uint64_t count, const ReverseQuery* query,
                std::vector<std::vector<Neighbour>>* columns,
                std::vector<std::vector<Neighbour>>* reverse, SearchStats* stats) const;

  const PoseFeatures& features_;
  NeighbourRules rules_;
  ExactSearchOptions options_;
};

// The frames j that NeighbourRules::Excluded(t, j, ...) excludes for a column t form one range
// [begin, end) around t inside t's clip: t itself, and with exclusion_frames = r > 0 the frames
// of t's clip with |t - j| < r. `clip_first_frames` is ascending and starts with 0.
struct ExclusionRange {
  uint64_t begin = 0;
  uint64_t end = 0;
  bool Contains(uint64_t frame) const { return frame >= begin && frame < end; }
};
ExclusionRange ExclusionRangeOf(const NeighbourRules& rules, uint64_t frame, uint64_t frame_count);

// OK if `clip_first_frames` starts with 0 and is ascending; InvalidArgument otherwise.
Status ValidateClipStarts(const std::vector<uint64_t>& clip_first_frames);

}  // namespace motif
