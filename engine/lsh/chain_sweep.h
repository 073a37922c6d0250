// ChainSweep: one column's step of a chain sweep (docs/design/lsh.md, section 3b). Once a chain's
// columns are found, sweeps over it, alternately backward and forward, carry every path found at
// any column of the chain to all of them: backward, column t verifies the frames j - 0..
// chain_advance for every neighbour j of column t + 1 that it does not hold yet; forward, the
// frames j + 0..chain_advance of column t - 1's. Both lists are sorted by frame, so the
// candidates come out of one merging walk, each once, with no set; they are verified with the
// exact D against the column's k_max-th distance before the sweep, and the column keeps its
// k_max nearest (ties: lower frame), sorted by frame: the column FinishColumn would make of
// both lists.
// Owns its scratch (candidates, accepted, merged) and a QueryDistance; refers to the features and
// rules, which must outlive it.
// Thread-safety: one per query worker.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/exclusion_filter.h"
#include "engine/lsh/lsh_query_stats.h"
#include "engine/lsh/query_distance.h"

namespace motif {

class ChainSweep {
 public:
  ChainSweep(const PoseFeatures& features, const NeighbourRules& rules, uint32_t chain_advance);

  // Column `column` (*out, found already, sorted by frame) verifies the frames of `from` (the
  // neighbours of column + direction, sorted by frame) moved by -direction * (0..chain_advance)
  // that it does not hold yet, and keeps the k_max nearest, sorted by frame. `direction` +1: from
  // the successor (a backward sweep); -1: from the predecessor (forward). Adds the evaluations to
  // *work.
  void Sweep(uint64_t column, const std::vector<Neighbour>& from, int direction,
             std::vector<Neighbour>* out, ColumnWork* work);

 private:
  // The candidates into candidates_: the union of [j - advance, j] (direction +1) or
  // [j, j + advance] (-1) over the frames j of `from`, less the frames `held` holds and those
  // excluded from the column, in increasing order.
  void CollectCandidates(uint64_t column, const std::vector<Neighbour>& from, int direction,
                         const std::vector<Neighbour>& held);
  // Verifies candidates_ against `bound` in prefetched batches: the accepted ones, in frame
  // order, into accepted_. Returns how many were within eps.
  uint64_t VerifyCandidates(float bound);
  // Merges accepted_ into *out (both by frame) and drops the farthest beyond k_max.
  void MergeAccepted(std::vector<Neighbour>* out);

  const PoseFeatures& features_;
  const NeighbourRules& rules_;
  const int64_t advance_;
  ExclusionFilter exclusion_;
  QueryDistance distance_;
  std::vector<uint32_t> candidates_;
  std::vector<Neighbour> accepted_;
  std::vector<Neighbour> merged_;
};

}  // namespace motif
