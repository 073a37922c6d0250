// ReversePass: the reverse scan of an incremental update (LshSearch::SearchColumnsAndReverse):
// the older frames whose columns a new frame n may enter. n enters an old column t when D(n, t)
// is within t's own threshold (its k_max-th distance, or eps), which may well be farther than
// n's own radius: so n's probed buckets are scanned breadth first out to eps, not to n's
// shrinking radius as the forward query does, and an older frame is skipped without an
// evaluation once its lower bound exceeds its column's threshold. Bucket collisions and
// sort-value gaps are symmetric in n and t, so this finds what t's own query would find of n,
// within the budget. An older frame outside the probed buckets or beyond the budget is missed.
// Owns its probe sequence, bucket scanner, visited set, QueryDistance and batch (scratch reused
// across columns); refers to the LshSearch's parts through the context.
// Thread-safety: one per query worker.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/distance/neighbour_search.h"
#include "engine/lsh/bucket_scanner.h"
#include "engine/lsh/candidate_verifier.h"
#include "engine/lsh/exclusion_filter.h"
#include "engine/lsh/lsh_query_context.h"
#include "engine/lsh/probe_sequence.h"
#include "engine/lsh/query_distance.h"
#include "engine/lsh/visited_set.h"

namespace motif {

class ReversePass {
 public:
  explicit ReversePass(const LshQueryContext& context);

  // Appends to *out the older frames t < query.frame_limit, not excluded from column `column`,
  // with D(column, t) <= min(eps, thresholds[t]) found in the column's probed buckets, at most
  // `budget` evaluations (a frame whose threshold is negative is not wanted). `seeds`: the
  // previous column's reverse frames in the same chain (or null), verified first advanced by
  // 0..chain_advance frames (as a chained forward query verifies its predecessor's neighbours),
  // outside the budget. A frame may be appended that *out holds already.
  void Run(uint64_t column, const ReverseQuery& query, uint32_t budget,
           const std::vector<Neighbour>* seeds, std::vector<Neighbour>* out);

 private:
  class ScanRounds;  // the BucketVisitor of the scan

  // A frame's threshold: its column's own (negative: not wanted), or eps.
  float ThresholdOf(uint32_t frame) const {
    return query_->thresholds != nullptr ? query_->thresholds[frame] : context_.rules.eps;
  }
  void VerifySeeds(const std::vector<Neighbour>& seeds);
  // Verifies the batch: the frames within eps and their thresholds go to out_. Empties the
  // batch; returns how many were verified.
  uint32_t VerifyBatch();

  const LshQueryContext context_;
  ProbeSequence probes_;
  BucketScanner scanner_;
  ExclusionFilter exclusion_;
  VisitedSet visited_;
  QueryDistance distance_;
  // The current column's.
  uint64_t column_ = 0;
  uint32_t clip_ = 0;
  const ReverseQuery* query_ = nullptr;
  std::vector<Neighbour>* out_ = nullptr;
  uint32_t evaluations_ = 0;  // within the budget: the scan's, not the seeds'
  uint32_t batch_[kVerifyBatch];
  uint32_t batch_size_ = 0;
};

}  // namespace motif
