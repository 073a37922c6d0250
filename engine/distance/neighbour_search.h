// Neighbour, NeighbourRules and NeighbourSearch: the vocabulary shared by the ways of finding a
// trellis column (exact blocked brute force in engine/distance, LSH in engine/lsh).
//
// A column t of the matching trellis lists the frames j with D(f_t, f_j) <= eps, except
//   - t itself, and frames of the same clip with |t - j| < exclusion_frames (trivial matches);
// at most k_max of them: the nearest (ties: lower frame index first), then sorted by frame
// index for the path grower.
// Thread-safety: NeighbourRules is immutable; NeighbourSearch::SearchColumns is const and safe
// from many threads on disjoint outputs.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/trellis_file/trellis_column.h"
#include "motifmine/defaults.h"

namespace motif {

struct NeighbourRules {
  float eps = 0;                                // include D <= eps
  uint32_t k_max = motifmine::defaults::kKMax;  // at most this many per column, the nearest kept
  uint32_t exclusion_frames = 30;               // same clip and |t - j| < this: excluded
  std::vector<uint64_t> clip_first_frames;      // ascending, starts with 0

  // True if j may never be a neighbour of t (t itself, or too close in the same clip).
  bool Excluded(uint64_t t, uint64_t j, uint32_t clip_of_t, uint32_t clip_of_j) const {
    if (t == j) return true;
    if (clip_of_t != clip_of_j) return false;
    const uint64_t gap = t > j ? t - j : j - t;
    return gap < exclusion_frames;
  }
};

// Keeps the k_max nearest of `candidates` (distance, then frame index) and sorts them by frame.
inline void FinishColumn(uint32_t k_max, std::vector<Neighbour>* candidates) {
  auto nearer = [](const Neighbour& a, const Neighbour& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
  };
  if (candidates->size() > k_max) {
    std::nth_element(candidates->begin(), candidates->begin() + k_max, candidates->end(), nearer);
    candidates->resize(k_max);
  }
  std::sort(candidates->begin(), candidates->end(),
            [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
}

// Statistics of a search, summed over columns.
struct SearchStats {
  uint64_t columns = 0;
  uint64_t distance_evaluations = 0;  // exact D computations
  uint64_t neighbours = 0;            // after the k_max cap
  uint64_t capped_columns = 0;        // columns that had more than k_max within eps
};

// What an incremental update asks of a search besides the columns of new frames: the older
// frames each new column finds within eps that could enter those frames' own columns. D is
// symmetric bit for bit (PoseDistance(a, b) == PoseDistance(b, a)), so an older frame t with
// D(t, n) <= eps is a candidate of column t exactly when t is one of column n: the new frames'
// own queries find the old columns they change (Meng et al.'s neighbourhood is symmetric).
struct ReverseQuery {
  // Frames below this are the older ones whose columns may change.
  uint64_t frame_limit = 0;
  // frame_limit entries: a frame t is reported only at a distance <= thresholds[t] (at most eps:
  // a full column accepts nothing farther than its k_max-th neighbour). Null: eps for all.
  const float* thresholds = nullptr;
};

// OK if `query` fits an archive of `frame_count` frames; InvalidArgument naming `search`.
inline Status CheckReverseQuery(const ReverseQuery& query, uint64_t frame_count,
                                const char* search) {
  if (query.frame_limit <= frame_count) return Status::Ok();
  return Status::InvalidArgument(std::string(search) + ": reverse frame limit " +
                                 std::to_string(query.frame_limit) + " beyond " +
                                 std::to_string(frame_count) + " frames");
}

class NeighbourSearch {
 public:
  virtual ~NeighbourSearch() = default;
  // Fills (*columns)[i] with column first_column + i, for i < count, following the rules the
  // search was built with. Adds to *stats. Deterministic: the same for any thread count.
  virtual Status SearchColumns(uint64_t first_column, uint64_t count,
                               std::vector<std::vector<Neighbour>>* columns,
                               SearchStats* stats) const = 0;
  // The same columns (identical to SearchColumns'), and (*reverse)[i] (resized to count) the
  // frames t < query.frame_limit, not excluded from column first_column + i by the rules, that
  // the search evaluated at D <= min(eps, thresholds[t]), with that exact distance, in no
  // particular order. The exact search finds every one; an approximate search those it
  // verified. Errors as SearchColumns.
  virtual Status SearchColumnsAndReverse(uint64_t first_column, uint64_t count,
                                         const ReverseQuery& query,
                                         std::vector<std::vector<Neighbour>>* columns,
                                         std::vector<std::vector<Neighbour>>* reverse,
                                         SearchStats* stats) const = 0;
};

}  // namespace motif
